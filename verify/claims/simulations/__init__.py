"""Figure captions that describe runs: regenerated with heyoka and decided by two measures each.

Each check integrates the derived equations in double from the caption's initial
conditions (unstated values are chosen, said in the claim's ``reading``, and varied where the
outcome could depend on them), reads every qualitative statement of the panel with two
measures computed differently (:mod:`verify.behaviour`, :mod:`verify.circling`), and decides:
confirmed or erratum when the measures agree, not checkable (both numbers shown) when they
disagree, qualified when the panel's behaviour comes only from a finite perturbation while
the threshold it implies is wrong (the exact threshold from :mod:`verify.studies.thresholds`
and the perturbation that produces the figure, found by bisection, are stated).  Runs are at
most 20 s; their energy drift is reported.

Each figure's runs are computed once (cached) and shared by its panels' claims; the figure
data hang on the first panel's evaluation.

This module is the registry (:func:`claims`); the checks are by body: :mod:`.disk` (Figs. 2-6),
:mod:`.ring` (Figs. 9-12), :mod:`.hurricane` (the hurricane balls and their gyroscope, Figs.
15-20), on the runs and readings of :mod:`.runs`.
"""
from __future__ import annotations

from ..base import RESULT, Claim, definition
from .disk import (_check_fig2, _check_fig3_lhs, _check_fig3_rhs, _check_fig4_lhs, _check_fig4_rhs, _check_fig5_lhs,
                   _check_fig5_rhs, _check_fig6)
from .ring import (_check_fig10_lhs, _check_fig10_rhs, _check_fig11_lhs, _check_fig11_rhs, _check_fig12, _fig9_check)
from .hurricane import (_check_fig15_lhs, _check_fig15_rhs, _check_fig16_lhs, _check_fig16_rhs, _check_fig17_lhs,
                        _check_fig18_lhs, _check_fig18_rhs, _check_fig19_citation, _check_fig19_lhs, _check_fig19_rhs,
                        _check_fig19_sum, _check_fig20_lhs, _check_fig20_rhs)

DISK = "Thin disk and hoop (Eqs. 1-46)"
RING_SECTION = "Thick ring (Eqs. 47-62)"
HB_SECTION = "Hurricane balls (Eqs. 63-82)"
GY_SECTION = "Gyroscope and effective Lagrangian (Eqs. 83-100)"


# --- the registry ----------------------------------------------------------------------

def _sim(id, source, section, statement, check, quote, reading=None, tolerance="two measures (see detail)", **kw):
    return Claim(id, source, section, statement, check, "simulation", tolerance, quote=quote, reading=reading, **kw)


def claims() -> list:
    d = DISK
    return [
        _sim("fig-2", "Fig. 2", d, "the CM and L turn at the same constant rate phidot", _check_fig2,
             r"the forces/torques are designed to rotate the CM and precess \mathbf{L} at exactly the same constant rate: "
             r"$\dot{\phi}$",
             "a steady circle of Eq. 21 at theta0 = 1.8 (> pi/2 as drawn), phidot0 = 5 (the caption gives no numbers)"),
        _sim("fig-3-lhs", "Fig. 3 LHS", d, "0.1% above Eq. 32, alpha = .1: wobbles above and below pi/2", _check_fig3_lhs,
             (r"With $\dot{\psi}$ just 0.1% above the Eq. (32) minimum for stable straight-line motion, and an initial "
              r"deviation $\alpha = .1$, the disks wobbles above and below $\theta = \pi/2$.",
              "ϕ is generally small"),
             "alpha = .1 read as theta0 = pi/2 + 0.1; phidot0 not stated (both 0 and 2 psidot0 alpha0 are run)",
             known_failure="with alpha = .1 the disk stays above pi/2", severity=RESULT),
        _sim("fig-3-rhs", "Fig. 3 RHS", d, "90% of Eq. 32: phi increasing, a generally clockwise orbit", _check_fig3_rhs,
             r"ϕ shows a consistent increasing trend resulting in a generally clockwise orbit",
             "clockwise seen from above (z up); the orbit read as the sense in which the CM circles over the run",
             known_failure="the orbit is counter-clockwise, with phi", severity=RESULT),
        _sim("fig-4-lhs", "Fig. 4 LHS", d, "exact Eq. 21 start: circular motion, phi very linear", _check_fig4_lhs,
             r"Starting with exactly the right initial values for circular motion: Eq. (21), circular motion with "
             r"$\theta, \dot{\phi}, \dot{\psi}$ constant is achieved. Note the very linear ϕ",
             "theta0 = 1.3, phidot0 = 5 (not stated)"),
        _sim("fig-4-rhs", "Fig. 4 RHS", d, "phidot0 = 0: more chaotic, deep theta bows", _check_fig4_rhs,
             r"Starting with $\dot{\phi}_0 = 0$ (check the ϕ plot) and leaving everything else unchanged results in more "
             r"chaotic motion. Again note deep θ bows when disk changes direction."),
        _sim("fig-5-lhs", "Fig. 5 LHS", d, "10% above Eq. 41, alpha = .01: wobbles, omega3 in step, CM in a small circle",
             _check_fig5_lhs,
             r"With $\dot{\phi}$ just 10% above the Eq. (41) minimum for stable vertical diameter spinning and an initial "
             r"deviation $\alpha = .01$, the disks wobbles above and below $\theta = \pi/2$, ω_3 oscillates in step with θ "
             r"and the CM path is confined to a small circle.",
             "psidot0 not stated: the family member of the paper's linearisation, (2k+1) psidot0 = 2(k+1) phidot0 alpha0"),
        _sim("fig-5-rhs", "Fig. 5 RHS", d, "90% of Eq. 41: spirals out", _check_fig5_rhs,
             r"With $\dot{\phi}$ at 90% of the Eq. (41) minimum, the path spirals out from the origin and makes a big loop "
             r"before returning."),
        _sim("fig-6", "Fig. 6", d, "LHS: CM motion hard to detect; RHS: CM motion is round-off", _check_fig6,
             ("Note that the resulting CM motion would be hard to detect.", "The displayed CM motion is just round-off error."),
             tolerance="CM excursion between 1e-6 and 1e-3 R (LHS), below 1e-12 R (RHS)"),
    ] + more_claims()


def more_claims() -> list:
    r, hb, gy = RING_SECTION, HB_SECTION, GY_SECTION
    fig9_q = r"circular motion with $\theta_0 = .1$"
    return [
        _sim("fig-9-lhs", "Fig. 9 LHS", r, "psidot0 1% above the circle: clockwise CM motion", _fig9_check("LHS", -1),
             (fig9_q, "LHS: With ψ_0 just 1% above that for stable circular motion: see clockwise CM motion."),
             "ψ_0 read as the rate psidot0, '1% above' as |psidot0| 1% larger; the circle and its handedness are not "
             "stated: the CM-at-rest circle with phidot0 > 0 (its mirror image swaps the senses)",
             qualified="the senses hold for one unstated handedness only"),
        _sim("fig-9-rhs", "Fig. 9 RHS", r, "psidot0 1% below the circle: counter-clockwise CM motion", _fig9_check("RHS", +1),
             (fig9_q, "RHS: With ψ_0 just 1% below that for stable circular motion: see counter-clockwise CM motion."),
             "as for the LHS", qualified="the senses hold for one unstated handedness only"),
        _sim("fig-10-lhs", "Fig. 10 LHS", r, "psidot0 = 19.3: theta oscillates on one side of equilibrium", _check_fig10_lhs,
             (r"the ring is started with its CM almost ($\Delta\theta = .0002$) directly above the contact",
              r"With $\psi_0 = 19.3$, θ oscillates, but just on one side of equilibrium."),
             "ψ_0 read as the rate psidot0; the sign of Delta theta is not stated (both are run)"),
        _sim("fig-10-rhs", "Fig. 10 RHS", r, "psidot0 = 18.8: theta quickly exceeds pi/2", _check_fig10_rhs,
             (r"the ring is started with its CM almost ($\Delta\theta = .0002$) directly above the contact",
              r"RHS: With $\dot{\psi}_0 = 18.8$, θ quickly exceeds the limit of $\pi/2$."),
             "Delta theta read as +0.0002 (above cot^-1 h)",
             qualified="18.8 is above the linear threshold; the run leaves only through the finite offset"),
        _sim("fig-11-lhs", "Fig. 11 LHS", r, "phidot0 = 31.3, theta0 = 1.225: theta oscillates", _check_fig11_lhs,
             r"LHS: With $\dot{\phi}_0 = \sqrt{g/R} = 31.3$, $\theta_0 = 1.225$: θ oscillates."),
        _sim("fig-11-rhs", "Fig. 11 RHS", r, "phidot0 = 25.7, started near theta_0 = 1.205: theta quickly exceeds pi/2", _check_fig11_rhs,
             (r"where the ring is started near its equilibrium angle θ_0",
              r"RHS: With $\dot{\phi}_0 = 25.7$, $\theta_0 = 1.205$: θ quickly exceeds the limit of $\pi/2$."),
             "θ_0 = 1.205 read as the equilibrium angle the caption names (it is, to its digits: Fig. 11 RHS (angle)); "
             "the start 'near' it, not stated, read as the LHS's own offset above its equilibrium (+0.0104)",
             qualified="25.7 is above the linear threshold; the run leaves only through the finite offset"),
        _sim("fig-12", "Fig. 12", r, "Jalali et al.'s start: the CM and the top point A move differently; "
             "dimensionless time sets g = 1", _check_fig12,
             ("The CM may have rather different motion!",
              r"workers may use dimensionless time: $t \leftarrow t\sqrt{g/R}$ which effectively sets $g = 1$ in the "
              r"equations of motion."), tolerance="paths differ by > 1% of their extent and length"),
        definition("fig-13", "Fig. 13", r, "rolling friction needs a footprint, not a single contact point",
                   "a qualitative continuum-mechanics argument with no model or numbers to check",
                   quote="In the RHS the contact is a footprint not a single point."),
        _sim("fig-15-lhs", "Fig. 15 LHS", hb, r"exact start at $\sqrt{2.6 g/a}$: static, no CM motion", _check_fig15_lhs,
             "as expected all quantities are static with no CM motion"),
        _sim("fig-15-rhs", "Fig. 15 RHS", hb, "theta slightly off: stable oscillation", _check_fig15_rhs,
             "RHS: With θ slightly off we get oscillations. The solution is stable"),
        _sim("fig-16-lhs", "Fig. 16 LHS", hb, r"$\sqrt{25 g/a}$, $\theta_0 + .01$: oscillates (same as previous)", _check_fig16_lhs,
             ("Same as previous but with much faster spin",
              "LHS: Starting with θ .01 above the exact initial conditions for a static solution"),
             "the panel states no outcome of its own; 'same as previous' read as Fig. 15 RHS's stable oscillation"),
        _sim("fig-16-rhs", "Fig. 16 RHS", hb, "psidot0 +10%: theta bounces below the limit", _check_fig16_rhs,
             r"RHS: Starting with $\dot{\psi}_0$ 10% above that for a static solution. Note that θ bounces to angles "
             r"smaller than the 'limit'.", "the 'limit' is cos^-1(2/5) = 1.159 (see Fig. 16 (limit))"),
        _sim("fig-17-lhs", "Fig. 17 LHS", hb, "rho = 1.2, theta = 0.578: exact start is static (circular, CM moving)",
             _check_fig17_lhs, (r"Solutions with smaller θ (but CM motion): $\rho = 1.2, \theta = 0.578$",
                                "LHS: Starting with the exact initial conditions for a static (circular) solution")),
        definition("fig-17-rhs", "Fig. 17 RHS", hb, "theta 0.01 above the static solution (no outcome stated)",
                   "the panel states a start and no outcome (the run is shown in the figure)",
                   quote="RHS: Starting with θ 0.01 above that for a static solution."),
        _sim("fig-18-lhs", "Fig. 18 LHS", gy, r"sleeping: $\dot{\phi}_0 = \dot{\psi}_0 = .98 \sqrt{g/a}$ oscillates", _check_fig18_lhs,
             r"LHS: With $\dot{\phi}_0 = .98\sqrt{g/a}$, θ oscillates.",
             "psidot0 = phidot0 (the caption's heading); theta0 'near 0' read as 0.01"),
        _sim("fig-18-rhs", "Fig. 18 RHS", gy, r"sleeping: $.97 \sqrt{g/a}$ spirals out past $\pi/2$", _check_fig18_rhs,
             (r"‘Sleeping spin’ solutions, where the balls are started with near $\theta_0 = 0$",
              r"RHS: With $\dot{\phi}_0 = .97\sqrt{g/a}$, the CM spirals outward; θ eventually exceeds the limit of $\pi/2$."),
             "psidot0 = phidot0; theta0 'near 0' read as 0.01",
             qualified=".97 is above the linear threshold; the run leaves only through the finite start"),
        _sim("fig-19-lhs", "Fig. 19 LHS", gy, r"$\dot{\phi}_0 = 0$: $\dot{\psi}_0 = 1.95 \sqrt{g/a}$ oscillates", _check_fig19_lhs,
             r"LHS: With $\dot{\psi}_0 = 1.95\sqrt{g/a}$, θ oscillates.", "theta0 = 0.01 (not stated), phidot0 = 0"),
        _sim("fig-19-rhs", "Fig. 19 RHS", gy, r"$\dot{\phi}_0 = 0$: $\dot{\psi}_0 = 1.9 \sqrt{g/a}$ spirals out past $\pi/2$", _check_fig19_rhs,
             r"RHS: With $\dot{\psi}_0 = 1.9\sqrt{g/a}$, the CM spirals outward; θ eventually exceeds the limit of $\pi/2$.",
             "theta0 = 0.01 (not stated), phidot0 = 0"),
        _sim("fig-19-sum", "Fig. 19 (psi + phi)", gy, "psi + phi ~ constant while psi and phi vary wildly", _check_fig19_sum,
             (r"one can show $\psi + \phi \approx \text{constant}$",
              "While ψ and ϕ separately vary wildly the sum is nearly constant."),
             known_failure="phi + psi grows; phidot + psidot is what stays nearly constant", severity=RESULT),
        Claim("fig-19-citation", "Fig. 19 (citation)", gy, "the third component of Eqs. (81-2)", _check_fig19_citation,
              "algebra", "exact (sympy)", quote="From the third component of Eqs. (81-2)",
              known_failure="Eq. 82 has no third component: Eqs. 80-81 are meant", severity="typo"),
        _sim("fig-20-lhs", "Fig. 20 LHS", gy, "theta0 = .01, rho = 3.535: static and stable to small deviations",
             _check_fig20_lhs,
             r"LHS: If Eq. (82) is exactly satisfied (here with $\theta_0 = .01, \rho = 3.535$) we find static solutions "
             r"which are stable against small deviations.", "a small deviation read as +0.001 in theta0"),
        _sim("fig-20-rhs", "Fig. 20 RHS", gy, "larger deviations spiral out past pi/2", _check_fig20_rhs,
             r"RHS: With larger deviations the CM spirals outward; θ eventually exceeds the limit of $\pi/2$.",
             "a larger deviation read as +0.05 in theta0"),
    ]

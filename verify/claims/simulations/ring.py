"""The thick ring's figure captions (Figs. 9-12), regenerated and read by two measures each."""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from models.steady import steady_state
from verify.behaviour import leaves, one_side, oscillates
from verify.engine.single import solve
from verify.figure_starts import start as figure_start
from verify.studies.thresholds import threshold

from ..base import FigureData, RunData, decide, qualify, undecided
from .runs import (G, PRINTED_SET, RING_PRINTED, SQRT_G, _arrays, _bisect, _completed, _leaves_quietly, _sense, _verdict,
                   finite_offset, run, run_start)


def _ring_params() -> dict:
    """The paper's printed ring as floats (with g)."""
    return {k: float(v) for k, v in RING_PRINTED.items()} | {"g": G}


def _ring_steady_psidot(th, phd, params=None):
    """psidot making row 1 of Eq. 50 (derived) vanish at constant theta (Eq. 58 solved for psidot)."""
    p = params or _ring_params()
    I1, I3, h = p["I1"], p["I3"], p["h"]
    s, c = math.sin(th), math.cos(th)
    num = -phd**2 * (s * c * (1 + I3 - I1 - h**2) + h * math.cos(2 * th)) - G * (c - h * s)
    return num / (phd * ((1 + I3) * s + h * c))


def _ring_cm_rest_rates(th, sign, params=None):
    """The steady circle with the CM at rest (rho = cos - h sin): phidot from Eq. 58, psidot = -rho phidot."""
    p = params or _ring_params()
    I1, I3, h = p["I1"], p["I3"], p["h"]
    s, c = math.sin(th), math.cos(th)
    rho = c - h * s
    P = G * (c - h * s) / (rho * ((I3 + 1) * s + h * c) - (h * math.cos(2 * th) + (I3 - I1 + 1 - h * h) * c * s))
    phd = sign * math.sqrt(P)
    return phd, -rho * phd


def _ring_run(state, t_end, label, **kw):
    return run("ring", state, t_end, label, params=RING_PRINTED, **kw)


@lru_cache(maxsize=None)
def _fig9_runs():
    """theta0 = 0.1 on the circle with the CM at rest (the special circle of the text after Eq. 58),
    phidot0 > 0; |psidot0| 1% above and below.  Controls: the mirror image (phidot0 < 0) and three
    circles far from the CM-at-rest one (phidot0 = -10, -20, -40)."""
    phd, psd = _ring_cm_rest_rates(0.1, +1)
    out = {}
    for f, side in ((1.01, "LHS"), (0.99, "RHS")):
        out[side] = run_start(f"fig9-{side.lower()}", f"CM-at-rest circle, phidot0 > 0, |psidot0| x {f}")[1]
        out[side + " mirror"] = _ring_run({"theta": 0.1, "phidot": -phd, "psidot": -f * psd}, 10,
                                          f"mirror image, |psidot0| x {f}")[1]
    for rate in (-10.0, -20.0, -40.0):
        for f in (1.01, 0.99):
            out[(rate, f)] = _ring_run({"theta": 0.1, "phidot": rate, "psidot": f * _ring_steady_psidot(0.1, rate)}, 5,
                                       f"phidot0 = {rate:g}, psidot0 x {f}", n_eval=10001)[1]
    return out


def _fig9_check(side: str, want: int):
    def check():
        r = _fig9_runs()
        main, mirror = _sense(r[side]), _sense(r[side + " mirror"])
        other = _sense(r[("RHS" if side == "LHS" else "LHS")])
        far = "; ".join(f"phidot0 = {rate:g}: +1% {_sense(r[(rate, 1.01)]).word()}, -1% {_sense(r[(rate, 0.99)]).word()}"
                        for rate in (-10.0, -20.0, -40.0))
        said = "clockwise" if want < 0 else "counter-clockwise"
        detail = ("theta0 = 0.1; which circle and which handedness are not stated: the circle with the CM at rest "
                  f"(text after Eq. 58) with phidot0 > 0, |psidot0| changed by 1%; 10 s; {PRINTED_SET}. The "
                  "slow path is the CM with the nutation filtered out (the loops' own sense is not what the caption "
                  f"describes). The other panel's start: {other.word()}. Negative control, the mirror image "
                  f"(phidot0 < 0, the handedness of the paper's Fig. 8, psidot > 0): {mirror.strobe.text()}; "
                  f"{mirror.mean.text()} -- the senses swap, as a mirror image must. Circles far from the CM-at-rest "
                  f"one do not reverse: {far}")
        figures = ()
        if side == "LHS":
            figures = (FigureData("fig-09", "Fig. 9: ring circles at theta0 = 0.1, CM-at-rest circle, |psidot0| +-1%",
                                  (r["LHS"], r["RHS"])),)
        if not (main.agree and mirror.agree):
            return undecided(f"{main.strobe.text()}; {main.mean.text()}", f"{said} CM motion", detail, figures,
                             main.measures())
        reverses = other.agree and other.sign == -main.sign and mirror.sign == -main.sign
        if main.sign == want and reverses:
            return qualify(f"slow path {main.word()} ({main.strobe.text()}; {main.mean.text()})", f"{said} CM motion",
                           detail,
                           "the +-1% reversal is real, but the senses as printed hold only for one unstated choice: "
                           "phidot0 > 0 with '1% above' read as |psidot0| 1.01 times larger; with the handedness of "
                           "the paper's own Fig. 8 (psidot > 0, phidot < 0), or with 'above' read as the signed value, "
                           "they are swapped. Convention-free: |psidot0| 1% above the circle's makes the slow path "
                           "drift against phidot, 1% below with it; and only on circles within about 0.01 in rho of "
                           "the CM-at-rest one (theta0 = 0.1; circles at phidot0 = -10, -20, -40 keep the sense of "
                           "phidot)", figures=figures, measures=main.measures())
        return decide(False, f"slow path {main.word()}", f"{said} CM motion", detail,
                      correction=f"the slow path circles {main.word()}", figures=figures, measures=main.measures())
    return check


@lru_cache(maxsize=None)
def _fig10_runs():
    h = float(RING_PRINTED["h"])
    eq = math.atan2(1, h)  # cot^-1 h
    out = {"eq": eq, "threshold": float(threshold("ring", "straight-line", RING_PRINTED).value)}
    panels = {(2e-4, 19.3): "fig10-lhs", (2e-4, 18.8): "fig10-rhs"}  # the figure's starts; -2e-4: the other sign
    for d in (2e-4, -2e-4):
        for rate in (19.3, 18.8):
            label = f"psidot0 = {rate}, Delta theta = {d:+g}"
            out[(d, rate)] = (run_start(panels[(d, rate)], label)[1] if (d, rate) in panels else
                              _ring_run({"theta": eq + d, "psidot": rate}, 5, label, n_eval=10001)[1])
    out["free"] = _ring_run({"theta": eq + 2e-4, "psidot": 18.8}, 5, "psidot0 = 18.8, no events", n_eval=10001,
                            events=False)[1]
    # negative control of the path's deviation: the same rate from the equilibrium itself rolls straight
    out["straight"] = _ring_run({"theta": eq, "psidot": 19.3}, 5, "psidot0 = 19.3, Delta theta = 0", n_eval=10001)[1]
    out["delta*"] = _bisect(lambda d: _leaves_quietly("ring", {"theta": eq + d, "psidot": 18.8}, 5, RING_PRINTED), 0.0, 2e-4)
    return out


def path_deviation(d: RunData) -> tuple:
    """(distance along the starting line, largest distance from it, turn of the heading) of the CM path.

    The starting line is the CM's first direction of motion (from the first two output points);
    the heading's turn is read off the path itself (the direction of its last step against its
    first), a route apart from the Euler angle phi the run also carries."""
    x, y = np.array(d.x), np.array(d.y)
    ux, uy = x[1] - x[0], y[1] - y[0]
    norm = math.hypot(ux, uy)
    ux, uy = ux / norm, uy / norm
    along = (x - x[0]) * ux + (y - y[0]) * uy
    across = -(x - x[0]) * uy + (y - y[0]) * ux
    vx, vy = x[-1] - x[-2], y[-1] - y[-2]
    turn = math.atan2(ux * vy - uy * vx, ux * vx + uy * vy)
    return float(along[-1]), float(np.max(np.abs(across))), turn


def _check_fig10_lhs():
    r = _fig10_runs()
    reads = []
    for d in (2e-4, -2e-4):
        t, th, x, y, *_ = _arrays(r[(d, 19.3)])
        reads.append(one_side(t, th, r["eq"], f"Delta theta = {d:+g}: one side of equilibrium"))
        reads.append(oscillates(t, th, _completed(r[(d, 19.3)]), f"Delta theta = {d:+g}: theta oscillates"))
    lhs = r[(2e-4, 19.3)]
    along, across, turn = path_deviation(lhs)
    along0, across0, turn0 = path_deviation(r["straight"])
    detail = (f"theta0 = cot^-1 h +- 0.0002 (the caption's sign is not stated: both), phidot0 = 0; 5 s; {PRINTED_SET}. "
              f"The path deviates from a straight line ('as a result the path slowly deviates'): in 5 s the CM goes "
              f"{along:.3g} R along its starting line and {across:.3g} R to the side of it, its heading turned by "
              f"{turn:+.3f} rad (phi {lhs.phi[-1]:+.3f} rad); from Delta theta = 0 the same rate rolls straight "
              f"({across0:.1e} R to the side, heading {turn0:+.1e} rad). 19.3 is above the linear threshold "
              f"{r['threshold']:.4f}")
    return _verdict(reads, (True,) * 4, "", "theta oscillates on one side of equilibrium", detail,
                    figures=(FigureData("fig-10", "Fig. 10: ring rolling straight with its CM above the contact",
                                        (lhs, r[(2e-4, 18.8)])),))


def _fig10_rhs_rule():
    """The runs of Fig. 10 RHS under the one finite-offset rule: (readings, linearly stable, start offset,
    bracket) from the caption's start, and the same for the negative control (Delta theta = -0.0002)."""
    r = _fig10_runs()
    run_, free, below = r[(2e-4, 18.8)], r["free"], r[(-2e-4, 18.8)]
    read = leaves(run_.outcome, "rim_switch", run_.t[-1], free.t, free.theta, math.pi / 2,
                  name="Delta theta = +0.0002: theta exceeds pi/2")
    control = leaves(below.outcome, "rim_switch", below.t[-1], below.t, below.theta, math.pi / 2,
                     name="Delta theta = -0.0002: theta exceeds pi/2")
    stable = 18.8 > r["threshold"]
    return (([read], stable, 2e-4, r["delta*"]), ([control], stable, -2e-4, r["delta*"]))


def _check_fig10_rhs():
    r = _fig10_runs()
    (reads, stable, offset, bracket), _ = _fig10_rhs_rule()
    lo, hi = bracket
    thr = r["threshold"]
    below = r[(-2e-4, 18.8)]
    detail = (f"theta0 = cot^-1 h + 0.0002, phidot0 = 0; 5 s; {PRINTED_SET}. From Delta theta = -0.0002 the "
              f"ring stays ({below.outcome}, theta on one side)")
    expected = "psidot0 = 18.8: theta quickly exceeds the limit of pi/2 (unstable, unlike 19.3)"
    ev = finite_offset(reads, stable, offset, bracket, expected, detail,
                       qualification=f"the exact linear threshold of this straight-line motion is psidot0 = {thr:.6f} "
                                     f"s^-1 (closed form, derived equations), so 18.8 is linearly stable; the ring leaves "
                                     f"within 5 s only from a finite offset Delta theta > {hi:.3g} rad above cot^-1 h "
                                     f"(bisection: stays at {lo:.3g}); the caption's +0.0002 is {offset / hi:.1f} times that",
                       correction=f"from the caption's start the ring stays: 18.8 is above the linear threshold "
                                  f"{thr:.6f}, and it leaves only from offsets above {hi:.3g} rad")
    return ev if ev is not None else _verdict(reads, (True,), "", "theta quickly exceeds pi/2", detail)


@lru_cache(maxsize=None)
def _fig11_runs():
    root = float(steady_state("ring", "diameter-spin", "25.7", RING_PRINTED)["theta"])
    near = 1.225 - _fig11_lhs_root()  # the LHS's start above its equilibrium: the caption's 'near'
    out = {"root": root, "near": near, "threshold": float(threshold("ring", "diameter-spin", RING_PRINTED).value)}
    out["lhs"] = run_start("fig11-lhs", "phidot0 = sqrt(g/R), theta0 = 1.225")[1]
    out["start"] = run_start("fig11-rhs", f"phidot0 = 25.7, theta0 = equilibrium {near:+.4f} (the LHS's offset)")[1]
    out["start free"] = _ring_run({"theta": root + near, "phidot": 25.7}, 20, "the same, no events", events=False)[1]
    out["printed"] = _ring_run({"theta": 1.205, "phidot": 25.7}, 20, "phidot0 = 25.7, theta0 = 1.205 (printed)")[1]
    out["free"] = _ring_run({"theta": 1.205, "phidot": 25.7}, 20, "phidot0 = 25.7, theta0 = 1.205, no events",
                            events=False)[1]
    out["delta*"] = _bisect(lambda d: _leaves_quietly("ring", {"theta": root + d, "phidot": 25.7}, 20, RING_PRINTED),
                            0.0, 1e-3)
    return out


def _check_fig11_lhs():
    r = _fig11_runs()
    t, th, *_ = _arrays(r["lhs"])
    read = oscillates(t, th, _completed(r["lhs"]))
    return _verdict([read], (True,), "", "theta oscillates",
                    r"$\dot{\phi}_0 = \sqrt{g/R}$, $\theta_0 = 1.225$, $\dot{\psi}_0 = 0$; 20 s; "
                    f"{PRINTED_SET} (the steady angle at this rate is {float(_fig11_lhs_root()):.4f})",
                    figures=(FigureData("fig-11", "Fig. 11: ring 'diameter spin'",
                                        (r["lhs"], r["start"], r["printed"])),))


def _fig11_lhs_root():
    return float(steady_state("ring", "diameter-spin", repr(SQRT_G), RING_PRINTED)["theta"])


def _fig11_rhs_rule():
    """The runs of Fig. 11 RHS under the one finite-offset rule: the caption's start (the equilibrium
    plus the LHS's offset) and the negative control (the printed 1.205 taken as the start itself)."""
    r = _fig11_runs()
    s, sf, p, pf = r["start"], r["start free"], r["printed"], r["free"]
    read = leaves(s.outcome, "rim_switch", s.t[-1], sf.t, sf.theta, math.pi / 2,
                  name=f"from the equilibrium {r['near']:+.4f}: theta exceeds pi/2")
    control = leaves(p.outcome, "rim_switch", p.t[-1], pf.t, pf.theta, math.pi / 2,
                     name="from 1.205 itself: theta exceeds pi/2")
    stable = 25.7 > r["threshold"]
    return (([read], stable, r["near"], r["delta*"]), ([control], stable, 1.205 - r["root"], r["delta*"]))


def _check_fig11_rhs():
    r = _fig11_runs()
    (reads, stable, offset, bracket), ((control,), *_) = _fig11_rhs_rule()
    lo, hi = bracket
    thr, root, p = r["threshold"], r["root"], r["printed"]
    detail = (f"psidot0 = 0, phidot0 = 25.7; 20 s; {PRINTED_SET}. The equilibrium at 25.7 is {root:.6f}, which the "
              f"printed theta_0 = 1.205 names (Fig. 11 RHS (angle)); the caption starts the ring 'near' it and does not "
              f"say how near: read as the LHS's own offset, 1.225 - {_fig11_lhs_root():.6f} = {offset:+.4f}, so theta0 = "
              f"{root + offset:.6f}; the ring leaves at t = {r['start'].t[-1]:.3f} s ({r['start'].outcome}). Taken as "
              f"the start itself, 1.205 lies {1.205 - root:+.2e} from the equilibrium and the ring stays 20 s "
              f"({p.outcome}, theta from {min(p.theta):.4f} to {max(p.theta):.4f}): {control.text()}")
    ev = finite_offset(reads, stable, offset, bracket,
                       "phidot0 = 25.7: theta quickly exceeds the limit of pi/2 (unstable, unlike 31.3)", detail,
                       qualification=f"the exact linear threshold of this diameter spin is $\\dot{{\\phi}}_0 = {thr:.6f}$ "
                                     f"(derived equations, along the Eq. 62 branch), so 25.7 is linearly stable; the ring "
                                     f"leaves within 20 s only from a finite offset above the equilibrium {root:.6f}, more "
                                     f"than {hi:.3g} rad (bisection: stays at {lo:.3g}); the start read, the LHS's "
                                     f"{offset:+.4f}, is {offset / hi:.0f} times that, while from the printed 1.205 taken "
                                     f"as the start ({1.205 - root:+.2e}) the ring stays",
                       correction=f"from the caption's start the ring stays on its rim for 20 s: 25.7 is above the "
                                  f"linear threshold {thr:.6f}, and it leaves only from offsets above {hi:.3g} rad")
    return ev if ev is not None else _verdict(reads, (True,), "", "theta quickly exceeds the limit of pi/2", detail)


def _point_a(data, h):
    th, ph = np.array(data.theta), np.array(data.phi)
    return np.array(data.x) + h * np.sin(ph) * np.sin(th), np.array(data.y) - h * np.cos(ph) * np.sin(th)


def _check_fig12():
    """Jalali et al.'s start violates the contact condition: N/(Mg) turns negative 5 ms in.  The
    caption's statements are about what is plotted (the CM or the point A; dimensionless time),
    so they are decided on the rolling equations run without the contact event, and the
    loss of contact is reported."""
    h = float(RING_PRINTED["h"])
    start = {k: float(v) for k, v in figure_start("fig12").state.items()}  # pi/2 - .55, 4.5 sqrt(g/R)
    sol, cm = run_start("fig12", "CM (contact not enforced)")  # run without the contact event, 3001 points
    normal = np.array([float(v) for v in sol.normal_force])
    first = solve("ring", "3", {k: repr(v) for k, v in start.items()}, params=RING_PRINTED, n_eval=2)
    ax, ay = _point_a(cm, h)
    ext = lambda x, y: math.hypot(np.ptp(x), np.ptp(y))
    e_cm, e_a = ext(np.array(cm.x), np.array(cm.y)), ext(ax, ay)
    a_run = RunData("point A (top of the ring above C)", cm.t, cm.theta, cm.phi, cm.omega3, tuple(ax), tuple(ay),
                    cm.energy_drift, cm.outcome)
    _, scaled = run("ring", {"theta": start["theta"], "phidot": 4.5}, 3 * SQRT_G, "g = 1",
                    params=dict(RING_PRINTED, g="1"), events=False, n_eval=3001)
    th_scaled = np.interp(np.array(cm.t) * SQRT_G, scaled.t, scaled.theta)
    scale_err = float(np.max(np.abs(th_scaled - np.array(cm.theta))))
    separation = float(np.max(np.hypot(ax - np.array(cm.x), ay - np.array(cm.y))))
    length = lambda x, y: float(np.sum(np.hypot(np.diff(x), np.diff(y))))
    l_cm, l_a = length(np.array(cm.x), np.array(cm.y)), length(ax, ay)
    ok = separation > 0.01 * e_cm and abs(l_a / l_cm - 1) > 0.01 and scale_err < 1e-3
    measures = (("largest distance between the A and CM paths, / CM path extent", f"{separation / e_cm:.3f}"),
                ("path length of A / path length of the CM", f"{l_a / l_cm:.3f}"))
    return decide(ok, f"the point A path runs up to {separation:.3f} R from the CM path (extents {e_cm:.2f} R and {e_a:.2f} R, "
                      f"lengths {l_cm:.2f} R and {l_a:.2f} R); $g = 1$ with $t \\sqrt{{g/R}}$ reproduces $\\theta(t)$ to {scale_err:.1e} "
                      f"(interpolated between outputs). But the normal force N/(Mg) falls to {normal.min():.2f}: with the "
                      f"contact enforced the run stops at t = {float(first.t[-1]) * 1e3:.2f} ms ({first.outcome}); the ring "
                      "would leave the plane, and the rolling solution beyond that is not physical",
                  "the CM may move rather differently from A; dimensionless time sets g = 1",
                  f"3 s (not stated); {PRINTED_SET}; the caption's 'may' is read as: the two paths differ visibly "
                  "(by more than 1% of the path's extent, and in length by more than 1%)",
                  figures=(FigureData("fig-12", "Fig. 12: Jalali et al.'s start (contact not enforced: N < 0 from 5 ms); "
                                      "CM (left) and point A (right)", (cm, a_run)),), measures=measures)

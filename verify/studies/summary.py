"""The issue-4 results as data for the report: thresholds (linear and nonlinear) and spin-down.

The ring's rows are about "the paper's ring", so they are computed for the paper's printed
parameters (``models.ring.PRINTED``: I1 = 0.4993, I3 = 0.8727, h = 0.4344), labelled so, with the
value for the model's defaults (the exact annular cylinder, ``models.ring.ANNULAR``) beside it
wherever the digits shown differ; :func:`ring_parameter_comparison` measures each such number
under both sets.
"""
from __future__ import annotations

import math

import mpmath

from models import ring as ring_body
from models.common import PAPER_G
from models.steady import ring_theta0_limits, steady_state
from verify.precision import parse_precision

from .spindown import FAMILIES, family_quantities, family_state, precision_runs, spindown
from .thresholds import GROWTH, bracket, linear_path, nonlinear_path, threshold, variational_w2

#: The parameter set of "the paper's ring" in every row below, and the one it is compared with.
RING_SET, RING_OTHER_SET = "printed", "annular"
RING_PARAMS = ring_body.parameter_set(RING_SET)  # decimal strings: JSON-ready

THRESHOLD_CASES = (
    ("disk", "diameter-spin", {}), ("disk", "diameter-spin", {"k": "0.5"}),
    ("sliding-disk", "diameter-spin", {}), ("sliding-disk", "diameter-spin", {"k": "0.5"}),
    ("disk", "straight-line", {}), ("disk", "straight-line", {"k": "0.5"}),
    ("ring", "straight-line", RING_PARAMS), ("ring", "diameter-spin", RING_PARAMS),
    ("hurricane", "precession", {}), ("hurricane", "sleeping", {}), ("gyroscope", "sleeping", {}),
)
TILTS = ("1e-4", "1e-5", "1e-6")
SCAN_FACTORS = ("1.02", "1.1", "1.5", "2", "3", "5", "10")  # x the slow-spin limit (motions with no threshold)
SCAN_TILTS = ("1e-3", "1e-5")
PROTOCOLS = ((1e3, "10"), (1e6, "40"))  # (growth factor, t_end) of the linear-protocol brackets
THETAS = ("1e-1", "1e-2", "1e-4", "1e-6", "1e-8")


def _nstr(x, n=10):
    return mpmath.nstr(x, n)


def _other_params() -> dict:
    """The ring parameters of the comparison set, as JSON-ready decimal strings ({} for the defaults)."""
    if RING_OTHER_SET == "annular":
        return {}
    return ring_body.parameter_set(RING_OTHER_SET)


def _ring_set(model: str, params: dict):
    """The name of the ring parameter set ``params`` is, for a ring model; None otherwise."""
    return ring_body.parameter_set_name(params) if model.startswith("ring") else None


def _params_cell(row: dict) -> str:
    """The 'params' cell of a row: the ring's named set, else the overrides or 'defaults'."""
    name = row.get("parameter_set")
    if name == "printed":
        return "printed: " + ", ".join(f"{k} = {v}" for k, v in ring_body.PRINTED.items())
    if name == "annular":
        return "annular (defaults)"
    return str(row["params"] or "defaults")


def _beside(value: str, other) -> str:
    """``value``, with the other parameter set's value beside it when the digits shown differ."""
    return value if other is None or other == value else f"{value} ({RING_OTHER_SET}: {other})"


def ring_parameter_comparison(motion: str, dps: int = 30) -> list:
    """The numbers the report prints about the paper's ring, under the printed and the annular set.

    Parameters
    ----------
    motion : {"straight-line", "diameter-spin"}
        Which steady motion's numbers: straight line (threshold, cot^-1 h, Fig. 10's rates
        against the threshold) or diameter spin (threshold, the ends of the theta0 branch of
        Eq. 62, Fig. 11's equilibrium angles and rates against the threshold).
    dps : int
        Working digits.

    Returns
    -------
    list of dict
        One per quantity: ``quantity``, ``paper`` (what the paper prints, or what it leaves
        unprinted), ``printed`` and ``annular`` (12 significant digits), ``difference``
        (printed - annular, 3 digits) and ``agree_digits`` (how many significant digits both
        round to alike).
    """
    sets = {"printed": ring_body.parameter_set("printed"), "annular": {}}
    out = []

    def add(quantity, paper, f):
        with mpmath.workdps(dps):
            vals = {k: mpmath.mpf(f(p)) for k, p in sets.items()}
            diff = vals["printed"] - vals["annular"]
            agree = 0
            for n in range(1, 16):
                if mpmath.nstr(vals["printed"], n) != mpmath.nstr(vals["annular"], n):
                    break
                agree = n
            out.append({"quantity": quantity, "paper": paper, "printed": _nstr(vals["printed"], 12),
                        "annular": _nstr(vals["annular"], 12), "difference": mpmath.nstr(diff, 3),
                        "agree_digits": agree})

    rate = "psidot0" if motion == "straight-line" else "phidot0"
    add(f"linear threshold {rate}", "not printed (Fig. 10: 19.3 and 18.8)" if motion == "straight-line"
        else "not printed (Fig. 11: 31.3 and 25.7)", lambda p: threshold("ring", motion, p, dps).value)
    if motion == "straight-line":
        add("theta = cot^-1 h (CM above the contact)", "1.161 (Fig. 10)", lambda p: ring_theta0_limits(p, dps)["slow"])
        add("pi/2 - cot^-1 h (tilt to the rim switch)", "-",
            lambda p: mpmath.pi / 2 - ring_theta0_limits(p, dps)["slow"])
        add("Fig. 10 RHS: 18.8 / threshold - 1 (%)", "-",
            lambda p: 100 * (mpmath.mpf("18.8") / threshold("ring", motion, p, dps).value - 1))
        return out
    add("theta0, slow-spin end: cot^-1 h", "1.16 (after Eq. 62)", lambda p: ring_theta0_limits(p, dps)["slow"])
    add("theta0, fast-spin end (Eq. 62 as derived, - h^2)", "- (the erratum's 1.254)",
        lambda p: ring_theta0_limits(p, dps)["fast"])
    add("theta0, fast-spin end (the paper's + h^2)", "1.32 (after Eq. 62; + h^2 is an erratum)",
        lambda p: ring_theta0_limits(p, dps)["fast_as_printed"])
    add("theta0 at phidot0 = 31.3 (Fig. 11 LHS)", "1.225 (Fig. 11; an erratum: the start is not the equilibrium)",
        lambda p: steady_state("ring", motion, "31.3", p)["theta"])
    add("theta0 at phidot0 = 25.7 (Fig. 11 RHS)", "1.205 (Fig. 11)",
        lambda p: steady_state("ring", motion, "25.7", p)["theta"])
    add("Fig. 11 RHS: 25.7 / threshold - 1 (%)", "-",
        lambda p: 100 * (mpmath.mpf("25.7") / threshold("ring", motion, p, dps).value - 1))
    return out


def threshold_rows(progress=None) -> list:
    """Linear threshold, nonlinear brackets at three tilts, linear-protocol brackets, variational w2."""
    rows = []
    for model, motion, params in THRESHOLD_CASES:
        if progress:
            progress(f"threshold {model} {motion} {params or ''}")
        t = threshold(model, motion, params)
        row = {"model": model, "motion": motion, "params": params, "rate": t.name,
               "linear": None if t.value is None else mpmath.nstr(t.value, 15),
               "closed_form": t.closed_form, "method": t.method, "brackets": {}, "linear_protocol": [],
               "variational": []}
        if _ring_set(model, params):
            other = threshold(model, motion, _other_params()).value
            row.update({"parameter_set": _ring_set(model, params),
                        RING_OTHER_SET: {"params": _other_params(), "linear": mpmath.nstr(other, 15)},
                        "parameter_sets": ring_parameter_comparison(motion)})
        if t.value is not None:
            for tilt in TILTS:
                lo, hi = bracket(model, motion, tilt, params, iterations=16)
                row["brackets"][tilt] = [_nstr(lo), _nstr(hi)]
            for growth, t_end in PROTOCOLS:
                lo, hi = bracket(model, motion, "1e-6", params, iterations=30, t_end=t_end, criterion="linear",
                                 growth=growth)
                row["linear_protocol"].append({"growth": growth, "t_end": t_end, "bracket": [_nstr(lo), _nstr(hi)]})
        else:
            row["scan"] = stability_scan(model, motion, params)
        if motion != "sleeping":
            with mpmath.workdps(40):
                base = t.value if t.value is not None else mpmath.sqrt(mpmath.mpf(PAPER_G) / mpmath.mpf("0.4")) * 2
            for factor in ("0.9", "1.1"):
                with mpmath.workdps(40):
                    rate = base * mpmath.mpf(factor)
                for precision in ("double", "quad"):
                    v = variational_w2(model, motion, rate, params, precision)
                    row["variational"].append({
                        "rate": _nstr(v.rate, 12), "precision": precision, "w2_linear": _nstr(v.w2_linear, 15),
                        "w2_variational": _nstr(v.w2_variational, 15),
                        "relative_difference": mpmath.nstr(v.relative_difference, 2),
                        "multipliers": [f"{round(m.real, 6) + 0.0:.6f}{round(m.imag, 6) + 0.0:+.6f}i" for m in v.multipliers]})
        rows.append(row)
    return rows


def stability_scan(model: str, motion: str, params: dict) -> list:
    """Nonlinear confirmation where the linearisation finds no threshold (hurricane precession).

    Rates from just above the slow-spin limit sqrt(g/I3) (cos(theta0) = 0: the upper ball
    touches the plane) to 10 times it; the protocol of the brackets (theta + tilt, rates
    kept, 10 s, full equations in double).  The extremes of theta - theta_steady are compared
    with the linearisation's d* + (tilt - d*) cos(sqrt(w2) t), whose lower extreme 2 d* - tilt
    depends on the rate: agreement of both extremes, not just staying bounded, is the check.
    """
    with mpmath.workdps(40):
        pv = {k: mpmath.mpf(v) for k, v in threshold(model, motion, params).params.items()}
        low = mpmath.sqrt(pv["g"] / pv["I3"])
    rows = []
    for factor in SCAN_FACTORS:
        with mpmath.workdps(40):
            rate = low * mpmath.mpf(factor)
        for tilt in SCAN_TILTS:
            outcome, path = nonlinear_path(model, motion, rate, tilt, params)
            lin = linear_path(model, motion, rate, tilt, params)
            tl = float(tilt)
            rows.append({"factor": factor, "rate": _nstr(rate, 12), "tilt": tilt, "outcome": outcome,
                         "theta_steady": _nstr(mpmath.mpf(steady_state(model, motion, rate, params)["theta"]), 12),
                         "nonlinear_range": [f"{min(path) / tl:.6f}", f"{max(path) / tl:.6f}"],
                         "linear_range": [f"{min(lin) / tl:.6f}", f"{max(lin) / tl:.6f}"],
                         "stays": outcome == "ok" and max(abs(v) for v in path) <= GROWTH * tl})
    return rows


def _verdict(caption_stable: bool, linearly_stable: bool, rate, crit) -> str:
    if caption_stable == linearly_stable:
        return "agrees"
    above = float(mpmath.mpf(rate) / crit - 1) * 100
    return (f"finite-amplitude: the rate is {above:+.2f}% from the threshold, linearly "
            f"{'stable' if linearly_stable else 'unstable'}; the panel's outcome comes from the size of the start offset")


def caption_rows() -> list:
    """The captions of Figs. 5, 10, 11, 18, 19 against the exact thresholds (and Olsson's)."""
    from verify.engine.single import solve

    from .thresholds import linear_deviation

    g = mpmath.mpf(PAPER_G)
    root_g = mpmath.sqrt(g)
    rows = []
    rolling = threshold("disk", "diameter-spin").value
    smooth = threshold("sliding-disk", "diameter-spin").value
    for f, says in (("1.1", "stable (wobbles, small circle)"), ("0.9", "unstable (spirals out)")):
        rate = rolling * mpmath.mpf(f)
        rows.append({"figure": "Fig. 5", "case": f"phidot0 = {f} x Eq. 41 = {_nstr(rate, 6)}", "caption": says,
                     "exact": f"rolling threshold {_nstr(rolling, 8)}: {'stable' if rate > rolling else 'unstable'}; "
                              f"Olsson's g/k {_nstr(smooth, 8)}: {'stable' if rate > smooth else 'unstable'}",
                     "verdict": _verdict(f == "1.1", rate > rolling, rate, rolling)})
    # the paper's ring: its printed parameters, the annular value beside where the digits shown differ
    ring, other = RING_PARAMS, _other_params()
    where = f"{RING_SET} parameters"
    ring_straight = threshold("ring", "straight-line", ring).value
    other_straight = threshold("ring", "straight-line", other).value
    eq = mpmath.mpf(steady_state("ring", "straight-line", 19, ring)["theta"])
    rim = mpmath.pi / 2 - eq
    other_rim = mpmath.pi / 2 - mpmath.mpf(steady_state("ring", "straight-line", 19, other)["theta"])
    for rate, says in (("19.3", "oscillates on one side"), ("18.8", "quickly exceeds pi/2")):
        lin = linear_deviation("ring", "straight-line", rate, "2e-4", ring, t_end="5")
        runs = []
        for tilt in (2e-4, 2e-6):
            sol = solve("ring", "5", {"theta": mpmath.nstr(eq + tilt, 20), "psidot": rate}, ring, n_eval=801)
            runs.append(f"tilt {tilt:g}: {sol.outcome}, max |dtheta| {max(abs(float(v) - float(eq)) for v in sol['theta']):.3g}")
        stable = mpmath.mpf(rate) > ring_straight
        rows.append({"figure": "Fig. 10", "case": f"psidot0 = {rate}, dtheta = 2e-4", "caption": says,
                     "parameter_set": RING_SET, "params": dict(ring),
                     "exact": f"threshold ({where}) {_beside(_nstr(ring_straight, 10), _nstr(other_straight, 10))}: "
                              f"linearly {'stable' if stable else 'unstable'}; linear max |dtheta| in 5 s {lin:.3g} "
                              f"(rim at {_beside(f'{float(rim):.3f}', f'{float(other_rim):.3f}')}); nonlinear "
                              + "; ".join(runs),
                     "verdict": _verdict(rate == "19.3", stable, rate, ring_straight)})
    ring_diam = threshold("ring", "diameter-spin", ring).value
    other_diam = threshold("ring", "diameter-spin", other).value
    for rate, th0, says in (("31.3", "1.225", "oscillates"), ("25.7", "1.205", "quickly exceeds pi/2")):
        eq = mpmath.mpf(steady_state("ring", "diameter-spin", rate, ring)["theta"])
        other_eq = mpmath.mpf(steady_state("ring", "diameter-spin", rate, other)["theta"])
        stable = mpmath.mpf(rate) > ring_diam
        offset = mpmath.mpf(th0) - eq
        lin = linear_deviation("ring", "diameter-spin", rate, offset, ring, t_end="20")
        runs = []
        for scale in (1, 100):
            sol = solve("ring", "20", {"theta": mpmath.nstr(eq + offset / scale, 20), "phidot": rate}, ring, n_eval=801)
            runs.append(f"offset {float(offset / scale):+.2g}: {sol.outcome}, max |dtheta| "
                        f"{max(abs(float(v) - float(eq)) for v in sol['theta']):.3g}")
        shown, other_shown = mpmath.nstr(eq, 6, strip_zeros=False), mpmath.nstr(other_eq, 6, strip_zeros=False)
        beside = "" if shown == other_shown else f"; {RING_OTHER_SET}: {other_shown}"
        rows.append({"figure": "Fig. 11", "case": f"phidot0 = {rate}, theta0 = {th0} (equilibrium {shown}{beside})",
                     "caption": says, "parameter_set": RING_SET, "params": dict(ring),
                     "exact": f"threshold ({where}) {_beside(_nstr(ring_diam, 10), _nstr(other_diam, 10))}: "
                              f"linearly {'stable' if stable else 'unstable'}; linear max "
                              f"|dtheta| in 20 s {lin:.3g}; nonlinear " + "; ".join(runs),
                     "verdict": _verdict(rate == "31.3", stable, rate, ring_diam)})
    sleeping = threshold("hurricane", "sleeping").value
    for fig, phid, psid, says in (("Fig. 18", "0.98", "0.98", "oscillates"), ("Fig. 18", "0.97", "0.97", "spirals out"),
                                  ("Fig. 19", "0", "1.95", "oscillates"), ("Fig. 19", "0", "1.9", "spirals out")):
        w3 = (mpmath.mpf(phid) + mpmath.mpf(psid)) * root_g
        stable = w3 > sleeping
        runs = []
        for th0 in ("1e-2", "1e-4"):
            sol = solve("hurricane", "10", {"theta": th0, "phidot": mpmath.nstr(mpmath.mpf(phid) * root_g, 20),
                                            "psidot": mpmath.nstr(mpmath.mpf(psid) * root_g, 20)}, n_eval=801)
            lin = linear_deviation("hurricane", "sleeping", w3, th0, phidot0=mpmath.mpf(phid) * root_g)
            runs.append(f"theta0 {th0}: {sol.outcome}, max theta {float(max(sol['theta'])):.3g} (linear {min(lin, 99):.3g})")
        rows.append({"figure": fig, "case": f"phidot0 = {phid}, psidot0 = {psid} sqrt(g/a): omega3 = "
                                            f"{_nstr(w3 / root_g, 5)} sqrt(g/a)", "caption": says,
                     "exact": f"sleeping threshold {_nstr(sleeping / root_g, 8)} sqrt(g/a): linearly "
                              f"{'stable' if stable else 'unstable'}; " + "; ".join(runs),
                     "verdict": _verdict(says == "oscillates", stable, w3, sleeping)})
    return rows


def spindown_rows() -> list:
    """Exact steady spin-down states against Eqs. 45 and 61; the ring's for the paper's printed parameters,
    with the relative error of Eq. 61 for the annular set beside (``relative_error_annular``)."""
    rows = []
    for model in ("disk", "ring"):
        params = RING_PARAMS if model == "ring" else {}
        for family in FAMILIES:
            for th in THETAS:
                s = spindown(model, th, family, params)
                q = family_quantities(s)
                row = {"model": model, "family": family, "theta": th, "phidot": mpmath.nstr(s.phidot, 15),
                       "psidot": mpmath.nstr(s.psidot, 15), "energy": mpmath.nstr(s.energy, 15),
                       "paper": s.paper_source, "relative_error": mpmath.nstr(s.relative_error, 6),
                       **{k: mpmath.nstr(v, 6) for k, v in q.items()}}
                if model == "ring":
                    other = spindown(model, th, family, _other_params())
                    row.update({"parameter_set": RING_SET, "params": dict(params),
                                f"relative_error_{RING_OTHER_SET}": mpmath.nstr(other.relative_error, 6)})
                rows.append(row)
    return rows


FIG6 = (("Fig. 6 LHS as printed", {"theta": "0.01", "phidot": "-625.917", "psidot": "625.948"}),
        ("Fig. 6 RHS as printed", {"theta": "0.01", "phidot": "-626.104", "psidot": "626.073"}))


def precision_rows() -> list:
    """Fig. 6's states and both disk families down to theta = 1e-6 in double, quad and MPFR."""
    cases = list(FIG6) + [(f"{family}, theta {th}", family_state(th, family))
                          for family in FAMILIES for th in ("1e-2", "1e-4", "1e-6")]
    rows = []
    for label, state in cases:
        for r in precision_runs(label, state):
            eps = parse_precision(r.precision).eps
            rel = r.omega3_error / r.omega3_scale if r.omega3_scale > 1e-30 else None
            rows.append({"case": label, "precision": r.precision, "steps": r.steps, "t_end": mpmath.nstr(mpmath.mpf(r.t_end), 6),
                         "theta_error": f"{r.theta_error:.2g}", "omega3_over_phidot": f"{r.omega3_scale:.3g}",
                         "omega3_error_over_phidot": f"{r.omega3_error:.2g}",
                         "omega3_relative_error": None if rel is None else f"{rel:.2g}",
                         "omega3_digits_lost": None if rel is None else round(math.log10(max(rel, eps) / eps), 1),
                         "cm_error": f"{r.cm_drift:.2g}", "max_rel_energy_drift": f"{r.energy_drift:.2g}"})
    return rows


def _threshold_lines(thresholds: list, captions: list) -> list:
    lines = [
        "## Stability thresholds",
        "",
        "**Linear.** For each steady motion the reduced Jacobian (theta, thetadot, phidot, psidot) of the derived",
        "equations has characteristic polynomial lambda^2 (lambda^2 + w2) (the double zero is the two-parameter family",
        "of steady motions); the motion is oscillatory while w2 > 0. The sleeping motion (theta = 0, where Euler angles",
        "are singular) is linearised in the complex tilt u = theta exp(i phi): u'' = A u + i B u', stable while B^2 > 4A.",
        "",
        "**Verdict on the Olsson question.** Both numbers are right, each for its own contact. Rolling without slipping:",
        "phidot0^2 > g/(k+1) (the paper's Eq. 41: 784 s^-2, rate 28.0 for the disk). Frictionless plane: phidot0^2 > g/k",
        "(Olsson's result: 3920 s^-2, rate 62.61). Olsson's assumption, zero horizontal contact force, is exactly the",
        "smooth-plane model (`sliding-disk`): with no horizontal force the centre of mass cannot move sideways, the",
        "wobble gets no help from the friction force that, when rolling, supplies the centre-of-mass acceleration, and",
        "the stabilising gyroscopic term must beat g/k instead of g/(k+1). A real disk on a table rolls, so Eq. 41",
        "applies; the paper's Fig. 5 (1.1 and 0.9 x Eq. 41) is stable and unstable exactly as Eq. 41 says, while Olsson's",
        "bound would call both unstable.",
        "",
        "**The sleeping hurricane balls.** Eq. 95 (omega3^2 > 35 g/a) is the fixed-pivot bound with the wrong inertia,",
        "as the paper itself suspects ('way too big'). The exact linear condition for the rolling balls is",
        "omega3^2 > 4 g (I1 + 4)/(I3 + 2)^2 = 3.75 g/a, omega3 > 1.9365 sqrt(g/a), which Figs. 18 and 19 bracket; the",
        "fixed-pivot gyroscope needs omega3^2 > 8 g (I1 + 4)/I3^2 = 270 g/a (the paper's Eq. 93 with its tildes).",
        "",
        "**Nonlinear confirmation.** Protocol: start on the steady motion at the given rate, add the tilt to theta and",
        "keep the rates (for the sleeping motion theta = tilt, phidot = 0, psidot = rate); the body then moves on a",
        "neighbouring member of the family, and the test measures theta against the unperturbed steady angle: 'growth'",
        "= leaving the domain or moving more than 1000 x the tilt within 10 s (double, derived equations, full state).",
        "Bisection on the rate (16 halvings) gives the bracket. The same protocol applied to the linearised equations",
        "(closed form: theta oscillates about a neighbouring member displaced by -s tilt/w2, s = ce + df) gives the",
        "linear-protocol bracket, the tilt -> 0 limit of the nonlinear one; it differs from the threshold by the",
        "protocol's own resolution (a displacement that grows like 1/w2 near the threshold, and a growth rate too slow",
        "to show in the time allowed), and tends to it as the growth factor and the time grow (second linear column).",
        "",
        "| model | motion | params | rate | linear threshold | closed form | nonlinear bracket, tilt 1e-4 | 1e-5 | 1e-6 "
        "| linear protocol (1e3, 10 s) | linear protocol (1e6, 40 s) |",
        "|---|---|---|---|---:|---|---|---|---|---|---|",
    ]
    for r in thresholds:
        br = [f"[{r['brackets'][t][0]}, {r['brackets'][t][1]}]" if t in r["brackets"] else "-" for t in TILTS]
        lp = [f"[{p['bracket'][0]}, {p['bracket'][1]}]" for p in r["linear_protocol"]] or ["-", "-"]
        linear = _beside(r["linear"], r.get(RING_OTHER_SET, {}).get("linear")) if r["linear"] else "none (stable)"
        lines.append(f"| {r['model']} | {r['motion']} | {_params_cell(r)} | {r['rate']} | "
                     f"{linear} | {r['closed_form'] or '-'} | " + " | ".join(br + lp) + " |")
    lines += _ring_parameter_lines(thresholds)
    lines += _scan_lines(thresholds)
    lines += [
        "",
        "**Variational confirmation.** heyoka's variational equations (order 1) along the steady motion of the full",
        "equations give Phi(T) at a quarter nutation period T = pi/(2 sqrt|w2|); its reduced block has eigenvalues",
        "1, 1 (the family) and exp(+-sqrt(-w2) T), so w2 follows from its trace. Multipliers: +-i on the stable side,",
        "exp(+-pi/2) = 4.81, 0.208 on the unstable side. Not applicable to the sleeping motion (theta = 0).",
        "",
        "| model | motion | params | rate | precision | w2 (sympy) | w2 (variational) | relative difference | multipliers |",
        "|---|---|---|---:|---|---:|---:|---:|---|",
    ]
    for r in thresholds:
        for v in r["variational"]:
            lines.append(f"| {r['model']} | {r['motion']} | {_params_cell(r)} | {v['rate']} | {v['precision']} "
                         f"| {v['w2_linear']} | {v['w2_variational']} | {v['relative_difference']} | "
                         f"{', '.join(v['multipliers'])} |")
    lines += [
        "",
        "**Figure captions against the exact thresholds.** 'finite-amplitude' marks a panel whose outcome is real at the",
        "paper's start (the claims section confirms the simulations) but is not the linear stability the caption pairs",
        "it with: the rate lies on the stable side of the exact threshold, and a start 100 times closer stays close.",
        "",
        "| figure | case | caption | exact threshold and runs | verdict |",
        "|---|---|---|---|---|",
    ]
    for c in captions:
        lines.append(f"| {c['figure']} | {c['case']} | {c['caption']} | {c['exact']} | {c['verdict']} |")
    return lines


def render(studies: dict) -> str:
    lines = _threshold_lines(studies["thresholds"], studies["captions"])
    lines += _map_lines(studies.get("maps", []))
    lines += _spindown_lines(studies)
    lines += _dissipation_lines(studies.get("dissipation", []))
    return "\n".join(lines) + "\n"


def _spindown_lines(studies: dict) -> list:
    lines = [
        "",
        "## The theta -> 0 spin-down",
        "",
        "**Exact steady families** (thetadot = 0, 50 digits): on the family with the centre of mass at rest and on the",
        "family with no spin about the vertical, row 1 of the derived equations is linear in phidot^2. Relative error of",
        "the paper's Eq. 45 (disk) or Eq. 61 (ring) against them, and along each family: |omega|, the speed of the centre",
        "of mass and of the contact point over the floor (units R/s), N/(Mg), and the stability coefficient w2 (> 0:",
        "stable, nutation frequency sqrt(w2)).",
        "",
        "| model | family | theta | phidot | psidot | energy | paper | relative error | abs(omega) | v_CM | v_contact "
        "| N/(Mg) | w2 |",
        "|---|---|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|",
    ]
    for r in studies["spindown"]:
        model = f"{r['model']} ({r['parameter_set']})" if r.get("parameter_set") else r["model"]
        error = _beside(r["relative_error"], r.get(f"relative_error_{RING_OTHER_SET}"))
        lines.append(f"| {model} | {r['family']} | {r['theta']} | {r['phidot']} | {r['psidot']} | {r['energy']} "
                     f"| {r['paper']} | {error} | {r['omega']} | {r['v_cm']} | {r['v_contact']} "
                     f"| {r['normal_force']} | {r['w2']} |")
    lines += [
        "",
        "What diverges as theta -> 0: phidot and psidot (like theta^-1/2), the contact point's speed R |psidot|, and the",
        "nutation frequency sqrt(w2) (like theta^-1/2; the families stay linearly stable). What vanishes: |omega| (like",
        "theta^1/2), the energy above the flat rest state (like theta), and the centre-of-mass speed (exactly 0 on the",
        "first family; on the second like theta^3/2 for the disk and like theta^1/2 for the ring). N/(Mg) -> 1. For the disk Eq. 45 is exact on the",
        "family at rest; for the ring Eq. 61 tends to a wrong limit on both families (leading order: phidot^2 theta ->",
        "g/I1 at rest, g/(h^2 + I1) with no vertical spin; Eq. 61 has g(1 - h)/(h^2 + I1)).",
        "",
        "**Precision.** Each state runs 5 turns of phi in double, quad and MPFR (160 bits) and is compared with MPFR at 256",
        "bits. On the family with no vertical spin omega3 = psidot + phidot cos(theta) ~ -phidot theta^2: a cancellation",
        "of two numbers of size phidot, so the relative error of omega3 is about eps/theta^2 and 2 log10(1/theta) digits are",
        "lost whatever the precision; below theta ~ sqrt(eps) (1e-8 in double) none survive. At theta = 1e-6: "
        + _digits_sentence(studies["precision"]) + ". On the family at rest omega3 = 0 exactly, and what a run shows is",
        "round-off of size eps phidot: the centre of mass 'moves' by that much (the paper's Fig. 6 RHS remark). theta",
        "itself, the energy and the centre of mass keep their full precision over these runs: the families are stable.",
        "",
        "| case | precision | steps | t_end | theta error / theta0 | omega3 / phidot | omega3 error / phidot "
        "| omega3 relative error | digits of omega3 lost | CM position error (R) | max abs(E - E(0)) / abs(E(0)) |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in studies["precision"]:
        lines.append(f"| {r['case']} | {r['precision']} | {r['steps']} | {r['t_end']} | {r['theta_error']} "
                     f"| {r['omega3_over_phidot']} | {r['omega3_error_over_phidot']} | {r['omega3_relative_error'] or '-'} "
                     f"| {r['omega3_digits_lost'] if r['omega3_digits_lost'] is not None else '-'} | {r['cm_error']} "
                     f"| {r['max_rel_energy_drift']} |")
    return lines


def _ring_parameter_lines(thresholds: list) -> list:
    """The table of the ring's numbers under the printed and the annular parameter set."""
    rows = [(r["motion"], q) for r in thresholds for q in r.get("parameter_sets", [])]
    if not rows:
        return []
    lines = [
        "",
        "**The paper's ring: printed against annular parameters.** The paper prints the ring's I1 = 0.4993, I3 = 0.8727,",
        "h = 0.4344 (text after Eq. 62), four-digit roundings of its own annular-cylinder formulas for R = 3.66 cm,",
        "h = 1.59 cm, w = 0.5 cm (exactly 16720/33489, 58453/66978, 53/122: the model's defaults, `models.ring.ANNULAR`).",
        "The ring's rows above and the Fig. 10 and 11 rows below use the printed values (`models.ring.PRINTED`), with the",
        "annular value beside where the digits shown differ; here each number under both sets.",
        "",
        "| motion | quantity | the paper | printed set | annular set | printed - annular | significant digits that round alike |",
        "|---|---|---|---:|---:|---:|---:|",
    ]
    for motion, q in rows:
        lines.append(f"| {motion} | {q['quantity']} | {q['paper']} | {q['printed']} | {q['annular']} | {q['difference']} "
                     f"| {q['agree_digits']} |")
    return lines


def _scan_lines(thresholds: list) -> list:
    lines = []
    for r in thresholds:
        if not r.get("scan"):
            continue
        stays = all(x["stays"] for x in r["scan"])
        lines += [
            "",
            f"**No threshold: {r['model']} {r['motion']}.** The linearisation finds w2 > 0 at every rate from the slow-spin",
            "limit sqrt(g/I3) up, so there is nothing to bisect; the nonlinear confirmation is the same protocol at rates",
            "across that range: the extremes of (theta - theta_steady)/tilt over 10 s of the full equations against those",
            "of the linearisation (lower extreme 2 d*/tilt - 1, which depends on the rate). "
            + ("Every run stays, and the extremes agree." if stays else "NOT every run stays: see the table."),
            "",
            "| rate / slow-spin limit | rate | theta_steady | tilt | outcome | nonlinear range / tilt | linear range / tilt |",
            "|---:|---:|---:|---:|---|---|---|",
        ]
        for x in r["scan"]:
            lines.append(f"| {x['factor']} | {x['rate']} | {x['theta_steady']} | {x['tilt']} | {x['outcome']} "
                         f"| [{x['nonlinear_range'][0]}, {x['nonlinear_range'][1]}] "
                         f"| [{x['linear_range'][0]}, {x['linear_range'][1]}] |")
    return lines


def _digits_sentence(rows: list) -> str:
    parts = []
    for r in rows:
        if r["case"] == "zero-vertical-spin, theta 1e-6" and r["omega3_digits_lost"] is not None:
            digits = round(-math.log10(parse_precision(r["precision"]).eps))
            parts.append(f"{r['precision']} loses {r['omega3_digits_lost']:g} of its {digits} digits of omega3 "
                         f"(relative error {r['omega3_relative_error']})")
    return "; ".join(parts)


def _map_lines(maps: list) -> list:
    if not maps:
        return []
    lines = [
        "",
        "**Stability maps.** 100 spin rates (0.5 to 1.5 x the threshold) x 100 initial tilts (1e-6 to 1e-1), 10 s each,",
        "integrated as heyoka batch + ensemble runs of the reduced system; colour = log10(max |theta - theta_steady| / tilt).",
        "The linear threshold is the red line; the white contour is the growth-1000 classification of the bisection.",
        "Their speed (target: 10^4 trajectories in under 10 s on 2 cores) is measured alone by the benchmark stage,",
        "BENCHMARKS.md (here they share the machine with the conservation table); `python benchmarks/bench_map.py`",
        "compares it with a scalar loop and batch mode without the ensemble.",
        "",
        "| model | motion | trajectories | linear threshold | growth switch at tilt 1e-6 (grid) | figure |",
        "|---|---|---:|---:|---|---|",
    ]
    for m in maps:
        name = _ring_set(m["model"], m.get("params", {}))
        model = f"{m['model']} ({name or 'other parameters'})" if m["model"].startswith("ring") else m["model"]
        lines.append(f"| {model} | {m['motion']} | {m['trajectories']} | {m['linear_threshold']} | "
                     f"[{m['switch_at_tilt_1e-6'][0]}, {m['switch_at_tilt_1e-6'][1]}] | {m['figure']} |")
    for m in maps:
        lines += ["", f"![]({m['figure']})"]
    return lines


def _dissipation_lines(laws: list) -> list:
    if not laws:
        return []
    lines = [
        "",
        "**Dissipation toward theta -> 0** (models/dissipative.py). The conservative equations keep theta away from 0;",
        "two documented dissipative couples tau = -c sin^-n(theta) (omega1 e1 + omega2 e2) drive the disk down its",
        "family: n = 3 reproduces Moffatt's viscous air-film dissipation (Nature 404, 833) on the steady family, n = 2 a",
        "loss proportional to the square of the contact point's rate (McDonald & McDonald, arXiv:physics/0008227).",
        "The predicted laws theta ~ (t0 - t)^p, phidot ~ (t0 - t)^q are derived with sympy from the family's energy and",
        "the couple's power; the run starts on the exact steady state at theta = 0.1, records the dissipated work W",
        "alongside (E + W = E(0) checked), and the exponents are fitted without t0 from log|thetadot| against log theta.",
        "The fit window ends where the drift is no longer slow against the nutation (ratio 1e-3): that ratio grows like",
        "theta^-5/2 (Moffatt) or theta^-3/2 as theta falls, so no run follows either law all the way down; below that",
        "the disk stops circling and creeps flat. Time to the singularity and turns are finite for both laws.",
        "",
        "| law | c | p fitted | p predicted | q fitted | q predicted | fit window (theta) | t0 fitted (s) | turns to the "
        "singularity | E + W - E(0) (eps of E(0)) | finite time, turns |",
        "|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---|",
    ]
    for r in laws:
        f = r["fit"]
        lines.append(f"| {r['law']} | {r['c']} | {f['p']} | {f['p_predicted']} | {f['q']} | {f['q_predicted']} | "
                     f"[{f['window'][0]}, {f['window'][1]}] | {f['t0']} | {f['turns']} | {r['run']['energy_balance_eps']} | "
                     f"{r['family']['finite_time']}, {r['family']['finite_turns']} |")
    lines += ["", "![](figures/dissipation.png)"]
    return lines

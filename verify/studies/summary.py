"""The stability and spin-down studies as data for the report: thresholds (linear, nonlinear,
variational), the figure captions against them, the stability maps, the spin-down families and
their precision.
:mod:`verify.report.sections` renders these rows.

The ring's rows are about "the paper's ring", so they are computed for the paper's printed
parameters (``models.ring.PRINTED``: I1 = 0.4993, I3 = 0.8727, h = 0.4344), labelled so, with the
value for the model's defaults (the exact annular cylinder, ``models.ring.ANNULAR``) beside it
wherever the digits shown differ; :func:`ring_parameter_comparison` measures each such number
under both sets.
"""
from __future__ import annotations

import math

import mpmath
import numpy as np

from models import ring as ring_body
from models.common import PAPER_G
from models.steady import ring_theta0_limits, steady_state
from verify.engine.single import solve
from verify.precision import parse_precision

from .spindown import FAMILIES, family_quantities, family_state, precision_runs, spindown
from .finite_offset import ERRATUM, QUALIFIED, finite_offset_verdict
from .maps import stability_map, switch_bracket
from .thresholds import GROWTH, bracket, linear_deviation, linear_path, nonlinear_path, threshold, variational_w2

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


def with_other_set(value: str, other) -> str:
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
    """Linear threshold, nonlinear brackets at three tilts, linear-protocol brackets, variational w2:
    one row per case of :data:`THRESHOLD_CASES` (:func:`threshold_case_rows`)."""
    rows = []
    for model, motion, params in THRESHOLD_CASES:
        if progress:
            progress(f"threshold {model} {motion} {params or ''}")
        rows.extend(threshold_case_rows(model, motion, params))
    return rows


def threshold_case_rows(model: str, motion: str, params: dict) -> list:
    """The rows of :func:`threshold_rows` for one case of :data:`THRESHOLD_CASES` (one row; a list, so
    that the report can run the cases as separate jobs and concatenate them in order)."""
    t = threshold(model, motion, params)
    row = {"model": model, "motion": motion, "params": params, "rate": t.name,
           "linear": None if t.value is None else mpmath.nstr(t.value, 15),
           "closed_form": t.closed_form, "closed_form_tex": t.closed_form_tex, "method": t.method, "brackets": {}, "linear_protocol": [],
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
    return [row]


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


def _verdict(caption_stable: bool, linearly_stable: bool, rate, crit, outcomes=()) -> str:
    """'agrees', or the finite-amplitude case with the verdict of the one rule of :mod:`.finite_offset`
    (the claims apply the same rule): ``outcomes`` are those of the runs from the caption's start and
    from one 100 times closer to the equilibrium."""
    if caption_stable == linearly_stable:
        return "agrees"
    above = float(mpmath.mpf(rate) / crit - 1) * 100
    text = (f"finite-amplitude: the rate is {above:+.2f}% from the threshold, linearly "
            f"{'stable' if linearly_stable else 'unstable'}")
    rule = finite_offset_verdict(linearly_stable, outcomes[0] != "ok") if outcomes and not caption_stable else None
    closer = "stays" if outcomes[1:] == ("ok",) else "leaves too"
    if rule == QUALIFIED:
        return text + f"; the caption's start leaves and one 100 times closer {closer}: qualified (the one rule)"
    if rule == ERRATUM:
        return text + "; the caption's start stays: erratum (the one rule)"
    return text + "; the panel's outcome comes from the size of the start offset"


def caption_rows() -> list:
    """The captions of Figs. 5, 10, 11, 18, 19 against the exact thresholds (and Olsson's)."""
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
        runs, outcomes = [], []
        for tilt in (2e-4, 2e-6):
            sol = solve("ring", "5", {"theta": mpmath.nstr(eq + tilt, 20), "psidot": rate}, ring, n_eval=801)
            outcomes.append(sol.outcome)
            runs.append(f"tilt {tilt:g}: {sol.outcome}, max |dtheta| {max(abs(float(v) - float(eq)) for v in sol['theta']):.3g}")
        stable = mpmath.mpf(rate) > ring_straight
        rows.append({"figure": "Fig. 10", "case": f"psidot0 = {rate}, dtheta = 2e-4", "caption": says,
                     "parameter_set": RING_SET, "params": dict(ring),
                     "exact": f"threshold ({where}) {with_other_set(_nstr(ring_straight, 10), _nstr(other_straight, 10))}: "
                              f"linearly {'stable' if stable else 'unstable'}; linear max |dtheta| in 5 s {lin:.3g} "
                              f"(rim at {with_other_set(f'{float(rim):.3f}', f'{float(other_rim):.3f}')}); nonlinear "
                              + "; ".join(runs),
                     "verdict": _verdict(rate == "19.3", stable, rate, ring_straight, tuple(outcomes))})
    ring_diam = threshold("ring", "diameter-spin", ring).value
    other_diam = threshold("ring", "diameter-spin", other).value
    # the LHS prints its start, 1.225 (its equilibrium plus 0.0104); the RHS prints its equilibrium, 1.205,
    # and starts 'near' it: read, as in the claims, with the LHS's offset (verify.studies.finite_offset)
    near = mpmath.mpf("1.225") - mpmath.mpf(steady_state("ring", "diameter-spin", "31.3", ring)["theta"])
    for rate, th0, says in (("31.3", "1.225", "oscillates"), ("25.7", None, "quickly exceeds pi/2")):
        eq = mpmath.mpf(steady_state("ring", "diameter-spin", rate, ring)["theta"])
        other_eq = mpmath.mpf(steady_state("ring", "diameter-spin", rate, other)["theta"])
        stable = mpmath.mpf(rate) > ring_diam
        offset = mpmath.mpf(th0) - eq if th0 else near
        lin = linear_deviation("ring", "diameter-spin", rate, offset, ring, t_end="20")
        runs, outcomes = [], []
        for scale in (1, 100):
            sol = solve("ring", "20", {"theta": mpmath.nstr(eq + offset / scale, 20), "phidot": rate}, ring, n_eval=801)
            outcomes.append(sol.outcome)
            runs.append(f"offset {float(offset / scale):+.2g}: {sol.outcome}, max |dtheta| "
                        f"{max(abs(float(v) - float(eq)) for v in sol['theta']):.3g}")
        shown, other_shown = mpmath.nstr(eq, 6, strip_zeros=False), mpmath.nstr(other_eq, 6, strip_zeros=False)
        beside = "" if shown == other_shown else f"; {RING_OTHER_SET}: {other_shown}"
        start = (f"theta0 = {th0} (equilibrium {shown}{beside})" if th0 else
                 f"started near theta_0 = 1.205 (its equilibrium {shown}{beside}), read as the equilibrium "
                 f"{float(near):+.4f} (the LHS's offset)")
        rows.append({"figure": "Fig. 11", "case": f"phidot0 = {rate}, {start}",
                     "caption": says, "parameter_set": RING_SET, "params": dict(ring),
                     "exact": f"threshold ({where}) {with_other_set(_nstr(ring_diam, 10), _nstr(other_diam, 10))}: "
                              f"linearly {'stable' if stable else 'unstable'}; linear max "
                              f"|dtheta| in 20 s {lin:.3g}; nonlinear " + "; ".join(runs),
                     "verdict": _verdict(rate == "31.3", stable, rate, ring_diam, tuple(outcomes))})
    sleeping = threshold("hurricane", "sleeping").value
    for fig, phid, psid, says in (("Fig. 18", "0.98", "0.98", "oscillates"), ("Fig. 18", "0.97", "0.97", "spirals out"),
                                  ("Fig. 19", "0", "1.95", "oscillates"), ("Fig. 19", "0", "1.9", "spirals out")):
        w3 = (mpmath.mpf(phid) + mpmath.mpf(psid)) * root_g
        stable = w3 > sleeping
        runs, outcomes = [], []
        for th0 in ("1e-2", "1e-4"):
            sol = solve("hurricane", "10", {"theta": th0, "phidot": mpmath.nstr(mpmath.mpf(phid) * root_g, 20),
                                            "psidot": mpmath.nstr(mpmath.mpf(psid) * root_g, 20)}, n_eval=801)
            outcomes.append(sol.outcome)
            lin = linear_deviation("hurricane", "sleeping", w3, th0, phidot0=mpmath.mpf(phid) * root_g)
            runs.append(f"theta0 {th0}: {sol.outcome}, max theta {float(max(sol['theta'])):.3g} (linear {min(lin, 99):.3g})")
        rows.append({"figure": fig, "case": f"phidot0 = {phid}, psidot0 = {psid} sqrt(g/a): omega3 = "
                                            f"{_nstr(w3 / root_g, 5)} sqrt(g/a)", "caption": says,
                     "exact": f"sleeping threshold {_nstr(sleeping / root_g, 8)} sqrt(g/a): linearly "
                              f"{'stable' if stable else 'unstable'}; " + "; ".join(runs),
                     "verdict": _verdict(says == "oscillates", stable, w3, sleeping, tuple(outcomes))})
    return rows


#: The report's stability maps: (model, motion), 100 rates x 100 tilts each.
MAPS = (("disk", "diameter-spin"), ("sliding-disk", "diameter-spin"), ("disk", "straight-line"),
        ("ring", "straight-line"), ("ring", "diameter-spin"))


def map_rows(progress=None) -> tuple:
    """The report's stability maps (:data:`MAPS`): :func:`map_row` of each, as ``(rows, maps, timing)`` lists."""
    rows, maps, timing = [], [], []
    for model, motion in MAPS:
        if progress:
            progress(f"stability map {model} {motion} (10^4 trajectories)")
        row, smap, wall = map_row(model, motion)
        rows.append(row)
        maps.append(smap)
        timing.append(wall)
    return rows, maps, timing


def map_row(model: str, motion: str) -> tuple:
    """One stability map of 100 rates x 100 tilts (10 s each) by heyoka batch + ensemble.

    The rates run from 0.5 to 1.5 x the linear threshold, the tilts from 1e-6 to 1e-1; the ring
    is the paper's (printed parameters).  Returns ``(row, map, timing)``: the row for
    results.json (its figure's file name under ``figures/`` included), the
    :class:`~verify.studies.maps.StabilityMap`, for the figure, and the wall time.
    """
    params = dict(ring_body.parameter_set("printed")) if model == "ring" else None  # the paper's own ring
    lin = float(threshold(model, motion, params).value)
    smap = stability_map(model, motion, rates=np.linspace(0.5 * lin, 1.5 * lin, 100), tilts=np.logspace(-6, -1, 100),
                         params=params)
    lo, hi = switch_bracket(smap)
    row = {"model": model, "motion": motion, "params": params or {}, "figure": f"figures/map-{model}-{motion}.png",
           "trajectories": smap.n_trajectories,
           "t_end": smap.t_end, "linear_threshold": f"{lin:.12g}",
           "switch_at_tilt_1e-6": [f"{lo:.6g}", f"{hi:.6g}"]}
    timing = {"model": model, "motion": motion, "trajectories": smap.n_trajectories,
              "wall_seconds": round(smap.wall_seconds, 2), "batch_size": smap.batch_size}
    return row, smap, timing


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

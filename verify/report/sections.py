"""The studies' sections of REPORT.md -- stability thresholds, stability maps, the spin-down and its
precision, dissipation -- rendered from the rows of :mod:`verify.studies.summary` (results.json's
``studies``) and nothing else."""
from __future__ import annotations

import math

from models import ring as ring_body

from ..precision import parse_precision
from ..studies.finite_offset import RULE
from ..studies.summary import RING_OTHER_SET, TILTS, with_other_set


def _params_cell(row: dict) -> str:
    """The 'params' cell of a row: the ring's named set, else the overrides or 'defaults'."""
    name = row.get("parameter_set")
    if name == "printed":
        return "printed: " + ", ".join(f"{k} = {v}" for k, v in ring_body.PRINTED.items())
    if name == "annular":
        return "annular (defaults)"
    return ", ".join(f"{k} = {v}" for k, v in row["params"].items()) if row["params"] else "defaults"


def _closed_form_cell(row: dict) -> str:
    """The threshold's closed form, typeset ('-' where the linearisation gives none)."""
    return f"${row['closed_form_tex']}$" if row.get("closed_form_tex") else "-"


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
        linear = with_other_set(r["linear"], r.get(RING_OTHER_SET, {}).get("linear")) if r["linear"] else "none (stable)"
        lines.append(f"| {r['model']} | {r['motion']} | {_params_cell(r)} | {r['rate']} | "
                     f"{linear} | {_closed_form_cell(r)} | " + " | ".join(br + lp) + " |")
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
        "**Figure captions against the exact thresholds.** 'finite-amplitude' marks a panel whose outcome is not the",
        "linear stability the caption pairs it with: the rate lies on the stable side of the exact threshold, yet the",
        "caption says the motion leaves. " + RULE + " Here 'leaves' is the run from the caption's start (Fig. 11 RHS:",
        "the equilibrium plus the LHS's offset, as in the claims), with one 100 times closer beside it.",
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
        error = with_other_set(r["relative_error"], r.get(f"relative_error_{RING_OTHER_SET}"))
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
        name = ring_body.parameter_set_name(m.get("params", {})) if m["model"].startswith("ring") else None
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

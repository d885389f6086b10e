"""REPORT.md's section on bodies of revolution from their profiles, rendered from results.json's
``studies.bodies`` (:func:`verify.studies.bodies.rows`) and the reference index."""
from __future__ import annotations


def render_markdown(rows: list, index: dict, thresholds=None) -> list:
    """The section: the shipped bodies, the paper's bodies reproduced, the runs, the steady motions' thresholds
    (``thresholds``: :func:`verify.studies.body_thresholds.rows`, absent from an older results.json) and the
    reference cases."""
    lines = ["", "## Bodies of revolution from their profiles", "",
             "Any convex body of revolution is a body file (`models/bodies/*.toml`: a meridian profile, I1, I3, an "
             "optional domain; docs/bodies.md), run with `trajectory --body FILE` or as `body:NAME`. Its contact "
             "point is the profile's lowest point, derived exactly; its equations are the suite's one derivation "
             "for every body (paper Eqs. 5-8, 73). The paper's bodies, derived again from their profiles:", "",
             "| body file | built-in model | accelerations identical (sympy) | same expressions | same bits (1 s, double) "
             "| largest difference / (1 + abs(y)) |", "|---|---|---|---|---|---:|"]
    for r in rows:
        p = r.get("paper")
        if p:
            lines.append(f"| {r['name']} | {p['model']} | {_yes(p['identity'])} | {_yes(p['same_expressions'])} | "
                         f"{_yes(p['same_bits'])} | {p['max_rel_difference']:.1e} |")
    lines += ["", "Where the expressions differ (the disk's file has I1 and I3 where the model has k and 2k; the ring's "
                  "half_thickness is its h) the runs are other roundings of the same equations and differ at the "
                  "conditioning's level; the hurricane balls' file gives the same expressions term for term, and the "
                  "same bits.", "",
              "Every shipped body, run 1 s in double from its default start (its file's [start], else theta in the middle of its domain, "
              "phidot = 1, psidot = 10); drift = max abs(I - I(0)) / (eps x the invariant's term scale):", "",
              "| body | profile | I1, I3 | domain (ends) | outcome | steps | invariants: drift in eps |",
              "|---|---|---|---|---|---:|---|"]
    for r in rows:
        run = r["run"]
        # a curve's expressions in code spans: their '*' would otherwise be read as emphasis
        profile = f"{r['kind']}: " + ", ".join(f"{k} = `{v}`" if "*" in v else f"{k} = {v}" for k, v in r["profile"].items())
        domain = f"({r['domain'][0]}, {r['domain'][1]}) ({r['domain'][2]} / {r['domain'][3]})"
        drift = ", ".join(f"{k} {v:g}" for k, v in run["drift_in_eps"].items())
        lines.append(f"| {r['name']} | {profile} | {r['I1']}, {r['I3']} | {domain} | {run['outcome']} | "
                     f"{run['steps']} | {drift} |")
    if thresholds:
        lines += _thresholds(thresholds)
    cases = [e for e in index["cases"] if e["model"].startswith("body:")]
    if cases:
        lines += ["", "Reference cases of the new bodies (two MPFR runs, as every case; the Reference trajectories "
                      "section has their checks):", "",
                  "| case | body | t_end (s) | agreeing digits at t_end: min (component) | median |", "|---|---|---:|---|---:|"]
        lines += [f"| {e['name']} | {e['model']} | {e['t_end']} | {e['min_certified_digits_final']} "
                  f"({e['weakest_component']}) | {e['median_certified_digits_final']} |" for e in cases]
    return lines


def _thresholds(rows: list) -> list:
    lines = ["", "Steady motions and their linear stability thresholds, derived for any body of revolution "
                 "(`python -m verify threshold body:NAME MOTION`; the rate is omega3 for sleeping, in s^-1), each "
                 "checked by the full equations: runs 10 % below and above the threshold from the steady motion "
                 "tilted by 1e-4, the stable side staying within 1000 tilts for 10 s and the other growing (at 1, 30 "
                 "and 300 s^-1 where one stability holds at every rate); for the paper's bodies also against the "
                 "built-in model's own threshold (19 digits). The egg (a curve) is not analysed: sympy ran past "
                 "ten minutes on it.", "",
             "| body | motion | theta0 | rate | threshold (s^-1) | stable | full equations | built-in model |",
             "|---|---|---|---|---:|---|---|---|"]
    for r in rows:
        nl = r.get("nonlinear")
        full = "-" if nl is None else ("agrees" if nl["agrees"] else "DISAGREES") + " (grows: " + ", ".join(
            f"{float(rate):.4g} {'yes' if g else 'no'}" for rate, g in zip(nl["rates"], nl["grows"])) + ")"
        b = r.get("built_in")
        built = "-" if b is None else f"{b['model']}: {b['threshold'] or 'none'} ({'same' if b['agrees'] else 'DIFFERS'})"
        value = r["threshold"][:17] if r["threshold"] else "none"
        lines.append(f"| {r['body']} | {r['motion']} | {r['theta0']} | {r['rate']} | {value} | {r['stable']} | {full} "
                     f"| {built} |")
    return lines


def _yes(flag: bool) -> str:
    return "yes" if flag else "no"

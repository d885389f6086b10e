"""The report's Friction section from results.json (``studies.friction``, and the dissipation
study's fitted t0 beside the slip times): every number read from the data, none typed here."""
from __future__ import annotations

from .markup import text


def _run_note(r: dict) -> str:
    notes = []
    if r.get("same_run_as"):
        return f"drawn from the samples of '{r['same_run_as']}'"
    if r.get("contact_lost_t") is not None:
        how = "stops at contact_lost" if r["outcome"] == "event:contact_lost" else "contact not enforced"
        notes.append(f"{how}: N/(Mg) <= 0 from t = {r['contact_lost_t']} s (down to {r['normal_min']}; "
                     f"{r['points_without_contact']} of {r['points']} points); the largest mu_req is before")
    if r["outcome"] not in ("ok", "event:contact_lost"):
        notes.append(f"stops at {r['outcome'].removeprefix('event:')}, t = {r['t_end']} s")
    return "; ".join(notes) or ""


def _run_cells(r: dict, marks: dict) -> str:
    at = "-" if r["mu_max"] is None else f"{r['mu_max']} at {r['t_mu_max']} s ({r['band']})"
    note = _run_note(r)
    if note:
        marks.setdefault(note, f"({chr(ord('a') + len(marks))})")
        at += f" {marks[note]}"
    return at


def _notes(marks: dict) -> list:
    return ["", "; ".join(f"{mark} {text(note)}" for note, mark in marks.items()) + "."] if marks else []


def _steady_diff(row: dict, precisions) -> str:
    return " / ".join(row["cfunc"][p]["difference_in_eps_scale"] for p in precisions)


def _zero(row: dict) -> bool:
    return float(row["mu_closed"]) < 1e-30


def render_markdown(friction: dict, dissipation=None) -> list:
    """The ``## Friction`` section as Markdown lines."""
    steady = friction["steady"]
    bands = steady["bands"]
    lines = [
        "## Friction",
        "",
        "$\\mu_{\\mathrm{req}} = |F_h| / N$, the friction coefficient a rolling motion needs (paper Eq. 6,",
        "$\\mathbf{F} = M (\\mathbf{a}_C + g \\mathbf{Z})$, from the run's own accelerations: `sol.friction_required`);",
        "a table with less cannot hold the motion. Bands: " + ", ".join(bands) + ". For orientation only (rough",
        "figures, no measured source cited): a coin on glass about 0.2-0.5, rubber on wood up to about 1. Largest values are over each run's output grid, up to its first point with $N \\le 0$ if it loses contact.",
        "",
        "**Figure runs** (every run a caption's figure shows, as the claims run it):",
        "",
        "| figure | run | largest mu_req (band) |",
        "|---|---|---|",
    ]
    marks = {}
    lines += [f"| {r['figure']} | {text(r['run'], table=True)} | {_run_cells(r, marks)} |" for r in friction["figures"] if r.get("rolling")]
    lines += _notes(marks)
    sliding = sorted({r["model"] for r in friction["figures"] if not r.get("rolling")})
    if sliding:
        lines += ["", f"Runs without rolling contact (no friction to need): the {', '.join(sliding)} runs."]
    ref = friction["reference"] or []
    points = sorted({r["points"] for r in ref})
    lines += ["", f"**Reference cases** (each run in double on {', '.join(map(str, points))} points):", "",
              "| case | largest mu_req (band) |", "|---|---|"]
    marks = {}
    lines += [f"| {r['case']} | {_run_cells(r, marks)} |" for r in ref if r.get("rolling")]
    lines += _notes(marks)
    others = [r["case"] for r in ref if not r.get("rolling")]
    if others:
        lines += ["", f"Without rolling contact (smooth plane, pivot, effective Lagrangian): {', '.join(others)}."]
    lines += _steady_lines(steady)
    lines += _slip_lines(friction, steady, dissipation)
    lines += _coulomb_lines(friction.get("coulomb"))
    return lines


def _coulomb_lines(examples) -> list:
    """Rolling and sliding with Coulomb friction (``disk+coulomb``): the examples' phases and balances."""
    if not examples:
        return []
    lines = ["", "**Rolling and sliding** (`disk+coulomb`: the disk rolls, or slides with F_h = -mu N u/|u|, switching at",
             "heyoka's events; `verify.engine.hybrid`). A skid launched with the wrong centre-of-mass velocity, the",
             "steady circle of Le Saux, Leine & Glocker (our reading of their rho) given less friction than it needs, so that",
             "its slip starts from s = 0, and that circle tilted off its steady motion with mu between the extremes of its",
             "mu_req, which rolls until mu_req reaches mu and slides from there (the emerging slip's direction is stiff like",
             "1/t^2: the slow solution's power series carries it to the first step, `verify.engine.slip_onset`). Phases",
             "from the double run; E + W (W the work of friction) in eps of E's term scale; the switch times of double and",
             "quad apart by at most the last column, in double's eps.", "",
             "| example | mu | phases (ends) | E + W drift, double / quad | switch times apart |", "|---|---|---|---|---|"]
    for e in examples:
        phases = "; ".join(f"{p['kind']} {p['t_start']}-{p['t_end']} s ({p['ended']})" for p in e["phases"])
        if not e["same_phases"]:
            phases += " (quad's phases differ)"
        need = f" (needs {e['need']})" if e.get("need") else ""
        balance = " / ".join(e["energy_plus_work_in_eps"][p] for p in ("double", "quad"))
        lines.append(f"| {text(e['example'], table=True)} | {e['friction']}{need} | {phases} | {balance} | "
                     f"{e['switch_gap_in_double_eps'] or '-'} |")
    return lines


def _steady_lines(steady: dict) -> list:
    precisions = steady["cfunc_precisions"]
    rows = steady["spindown"] + steady["motions"]
    present = [r for r in rows if not r.get("none")]
    worst = {p: max(float(r["cfunc"][p]["difference_in_eps_scale"]) for r in present) for p in precisions}
    agree = all(r["cfunc"][p]["agrees"] for r in present for p in precisions)
    lines = [
        "",
        "**Steady families, two ways.** On a steady motion the body turns rigidly about the vertical at Omega_C = phidot;",
        "no slip gives v_C = (r2 omega3 - r3 omega2) e1 for r_P = r2 e2 + r3 e3 (disk -e2, ring -e2 - h e3, hurricane balls",
        "-sin(theta) e2 - (1 + cos theta) e3), so C circles at radius rho_C = |v_C| / |phidot|, N = M g and",
        "mu_req = Omega_C^2 rho_C / g. This closed form (50 digits) against the engine's cfunc on the state rounded to "
        + " and ".join(precisions) + ", in units of eps S, S = 1 + |phidot| (|phidot| + |psidot|) / g (bound "
        f"{steady['agreement_factor']}): largest " + "; ".join(f"{p} {worst[p]:g}" for p in precisions)
        + (", every state agrees." if agree else ": NOT every state agrees (see the rows)."),
    ]
    zero = {}
    for r in present:
        if _zero(r):
            zero.setdefault((r["model"], r["family"]), []).append(r)
    if zero:
        lines += ["", "mu_req = 0 (rho_C = 0: C at rest or on a line) on every state of: "
                  + "; ".join(f"{m} {f} ({rs[0]['at']} to {rs[-1]['at']}; largest closed form "
                              f"{max(float(r['mu_closed']) for r in rs):.1e}, cfunc "
                              + ", ".join(f"{max(float(r['cfunc'][p]['mu']) for r in rs):.1e}" for p in precisions) + ")"
                              for (m, f), rs in zero.items())
                  + ". The disk's cm-at-rest family is the one on which the paper's Eq. 45 holds."]
    missing = [r for r in rows if r.get("none")]
    if missing:
        lines += ["", "No steady motion of the family exists at: "
                  + "; ".join(f"{r['model']} {r['family']} {r['at']}" for r in missing) + "."]
    lines += ["", "| family | theta | rho_C (R) | mu_req, closed form (band) | cfunc - closed form ("
              + " / ".join(precisions) + ", eps S) |", "|---|---|---|---|---|"]
    lines += [f"| {r['model']} {r['family']}{'' if r['at'].startswith('theta') else ', ' + r['at']} | {r['theta']} "
              f"| {r['rho_C']} | {r['mu_closed']} ({r['band']}) "
              f"| {_steady_diff(r, precisions)} |" for r in present if not _zero(r)]
    return lines


def _slip_lines(friction: dict, steady: dict, dissipation) -> list:
    levels = steady["mu_levels"]
    lines = ["", "**Where a spinning coin starts to slip.** Along each spin-down family, the tilts theta at which",
             "mu_req(theta) = mu (every root in the range scanned, the order a spin-down meets them; none where mu exceeds",
             "the family's largest mu_req):", "",
             "| model | family | largest mu_req (at theta) | " + " | ".join(f"theta at mu = {m}" for m in levels) + " |",
             "|---|---|---|" + "---|" * len(levels)]
    for f in steady["family_slip"]:
        if f.get("none"):
            continue
        cells = [", ".join(f["roots"][m]) or "none" for m in levels]
        lines.append(f"| {f['model']} | {f['family']} | {f['max_mu']} ({f['theta_at_max']}) | " + " | ".join(cells) + " |")
    laws = friction.get("slip") or {}
    if not laws:
        return lines
    drift = {law: v["drift"] for law, v in laws.items()}
    slip = {law: v["run"] for law, v in laws.items()}
    fitted = {d["law"]: d["fit"]["t0"] for d in (dissipation or [])}
    lines += ["", "On Eq. 45's family C is at rest: no friction needed, no slip. The dissipative runs start on it and leave it:",
              "omega3 grows as theta falls (Chaplygin's row 3, which the couple leaves unchanged), C circles and",
              "mu_req = |phidot omega3| / g grows. Where it reaches mu, two ways: (1) the dissipation study's quasi-steady drift",
              "(steady motions with omega3 transported in theta; its theta is the same for both laws), the root of",
              "mu_req(theta) = mu; (2) the damped run with the engine's slips event (on from shortly before (1)'s time; the run",
              "without it is checked below mu up to there). They differ in physics by the run's departure from the drift,",
              "of the order of the adiabatic parameter a = |dtheta/dt| / (theta phidot) at the slip, plus the start's",
              "nutation: that, not round-off, is the agreement to expect.",
              "", "| law | mu | theta (drift) | theta (run) | run/drift - 1 | a | t (drift, s) | t (run, s) | "
              "mu_req before switch / at event | t0 fitted - t (run, s) |", "|---|---|---|---|---|---|---|---|---|---|"]
    for law in sorted(set(drift) | set(slip)):
        d = {x["mu"]: x for x in drift.get(law, {}).get("levels", [])}
        s = {x["mu"]: x for x in slip.get(law, {}).get("legs", [])}
        for m in levels:
            a, b = d.get(m, {}), s.get(m, {})
            th_a, th_b = a.get("theta"), b.get("theta")
            rel = f"{float(th_b) / float(th_a) - 1:.2g}" if th_a and th_b else "-"
            t0 = fitted.get(law)
            before = f"{float(t0) - float(b['t']):.4g}" if t0 and b.get("t") else "-"
            run = th_b or (f"no slip ({b['outcome']})" if b else "-")
            at_event = f"{b.get('plain_max', '-')} / {b.get('mu_at_event', '-')}" if b else "-"
            lines.append(f"| {law} | {m} | {th_a or 'none'} | {run} | {rel} | {a.get('adiabatic', '-')} | {a.get('t', '-')} "
                         f"| {b.get('t', '-')} | {at_event} | {before} |")
    t0s = "; ".join(f"{law}: fitted {fitted.get(law, '-')} s, transported {drift.get(law, {}).get('t0_transported', '-')} s"
                    for law in sorted(set(drift) | set(slip)))
    lines += ["", f"The dissipation study's finite-time singularity t0: {t0s}. A positive last column: the slip comes first."]
    return lines

"""The report's Friction section from results.json (``studies.friction``, and the dissipation
study's fitted t0 beside the slip times): every number read from the data, none typed here."""
from __future__ import annotations

from .markup import text


def _run_note(r: dict) -> str:
    notes = []
    if r.get("same_run_as"):
        notes.append(f"the samples of '{r['same_run_as']}'")
    if r.get("contact_lost_t") is not None:
        how = "stops at contact_lost" if r["outcome"] == "event:contact_lost" else "contact not enforced"
        notes.append(f"{how}: N <= 0 from t = {r['contact_lost_t']} s ({r['points_without_contact']} of {r['points']} "
                     "points); mu_req meaningless there, its largest value is before")
    if r["outcome"] not in ("ok", "event:contact_lost"):
        notes.append(f"stops at {r['outcome'].removeprefix('event:')}, t = {r['t_end']} s")
    return "; ".join(notes) or ""


def _run_cells(r: dict) -> str:
    if not r.get("rolling"):
        return f"{r['model']} | no rolling contact | | | |"
    at = "-" if r["mu_max"] is None else f"{r['mu_max']} (t = {r['t_mu_max']} s)"
    return f"{r['model']} | {at} | {r['band']} | {r['normal_min']} | {text(_run_note(r))}"


def _steady_diff(row: dict, precisions) -> str:
    return " / ".join(row["cfunc"][p]["difference_in_eps_scale"] for p in precisions)


def _zero(row: dict) -> bool:
    return float(row["mu_closed"]) < 1e-30


def render_markdown(friction: dict, dissipation=None) -> list:
    """The ``## Friction`` section as Markdown lines."""
    steady = friction["steady"]
    bands, precisions = steady["bands"], steady["cfunc_precisions"]
    lines = [
        "## Friction",
        "",
        "The friction a rolling motion needs: mu_req = |F_h| / N, the horizontal contact force over the normal force,",
        "from the run's own accelerations (paper Eq. 6, F = M (a_C + g Z); `sol.friction_required`). A table whose",
        "friction coefficient is below a run's largest mu_req cannot hold that motion: the body would slip there. The",
        f"bands the tables use: {', '.join(bands)}. For orientation only, as the section's brief states them (no measured",
        "source is cited): a coin on glass about 0.2-0.5, rubber on wood up to about 1. The reader judges from the numbers.",
        "Each largest value is over the run's own output grid (points as listed in the figure's run), up to the first",
        "point with N <= 0 where a run loses contact.",
        "",
        "**Figure runs** (every run a caption's figure shows, regenerated as the claims run it):",
        "",
        "| figure | run | model | largest mu_req | band | min N/(Mg) | note |",
        "|---|---|---|---:|---|---:|---|",
    ]
    lines += [f"| {r['figure']} | {text(r['run'])} | {_run_cells(r)} |" for r in friction["figures"]]
    ref = friction["reference"] or []
    points = sorted({r["points"] for r in ref})
    lines += ["", f"**Reference cases** (each run in double on {', '.join(map(str, points))} points):", "",
              "| case | source | model | largest mu_req | band | min N/(Mg) | note |", "|---|---|---|---:|---|---:|---|"]
    lines += [f"| {r['case']} | {text(r['source'])} | {_run_cells(r)} |" for r in ref]
    lines += _steady_lines(steady)
    lines += _slip_lines(friction, steady, dissipation)
    return lines


def _steady_lines(steady: dict) -> list:
    precisions = steady["cfunc_precisions"]
    rows = steady["spindown"] + steady["motions"]
    present = [r for r in rows if not r.get("none")]
    worst = {p: max(float(r["cfunc"][p]["difference_in_eps_scale"]) for r in present) for p in precisions}
    agree = all(r["cfunc"][p]["agrees"] for r in present for p in precisions)
    lines = [
        "",
        "**Steady families, two ways.** On a steady motion the configuration turns rigidly about the vertical at",
        "Omega_C = phidot, and no slip gives v_C = (r2 omega3 - r3 omega2) e1 (r_P = r2 e2 + r3 e3: the disk -e2, the ring",
        "-e2 - h e3, the hurricane balls -sin(theta) e2 - (1 + cos theta) e3): C runs on a circle of radius",
        "rho_C = |r2 omega3 - r3 omega2| / |phidot|, N = M g, and mu_req = Omega_C^2 rho_C / g (`verify/studies/friction.py`).",
        "That closed form, at 50 digits, against the engine's friction cfunc on the same state rounded to "
        + " and ".join(precisions) + ": the difference in units of eps S, S = 1 + |phidot| (|phidot| + |psidot|) / g (the",
        f"size rounding gives mu; bound {steady['agreement_factor']} eps S). Largest difference over every state below: "
        + "; ".join(f"{p} {worst[p]:g}" for p in precisions) + (" eps S: every state agrees." if agree else
                                                                 " eps S: NOT every state agrees (see the rows)."),
    ]
    zero = {}
    for r in present:
        if _zero(r):
            zero.setdefault((r["model"], r["family"]), []).append(r)
    if zero:
        lines += ["", "On these mu_req = 0 at every state computed (rho_C = 0: C at rest or on a straight line), including the",
                  "disk's centre-of-mass-at-rest family, on which the paper's Eq. 45 holds: "
                  + "; ".join(f"{m} {f} ({len(rs)} states, {rs[0]['at']} to {rs[-1]['at']}; largest closed form "
                              f"{max(float(r['mu_closed']) for r in rs):.1e}, cfunc "
                              + ", ".join(f"{max(float(r['cfunc'][p]['mu']) for r in rs):.1e}" for p in precisions) + ")"
                              for (m, f), rs in zero.items()) + "."]
    missing = [r for r in rows if r.get("none")]
    if missing:
        lines += ["", "No steady motion of the family exists at: "
                  + "; ".join(f"{r['model']} {r['family']} {r['at']}" for r in missing) + "."]
    lines += ["", "| model | family | at | theta | phidot | rho_C (R) | mu_req (closed form) | band | cfunc - closed form ("
              + " / ".join(precisions) + ", eps S) |", "|---|---|---|---:|---:|---:|---:|---|---:|"]
    lines += [f"| {r['model']} | {r['family']} | {r['at']} | {r['theta']} | {r['phidot']} | {r['rho_C']} | {r['mu_closed']} "
              f"| {r['band']} | {_steady_diff(r, precisions)} |" for r in present if not _zero(r)]
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
    lines += ["", "A coin exactly on the paper's Eq. 45 family needs no friction, so that family never slips. The dissipative",
              "runs of the dissipation study start on it but do not stay: omega3 grows from 0 as theta falls (Chaplygin's",
              "row 3, unchanged by the couple), C circles, and mu_req = |phidot omega3| / g grows. Two routes to where it",
              "reaches mu: (1) the study's quasi-steady drift, steady motions with omega3 transported in theta (the same",
              "theta for both laws; only its clock depends on the couple), the root of mu_req(theta) = mu; (2) the damped",
              "run itself with the engine's slips event (switched on shortly before route 1's slip time, from the run without",
              "it, whose mu_req is checked below mu up to there). They differ in physics by the run's departure from the quasi-steady drift, of the order of the",
              "adiabatic parameter a(theta) = |dtheta/dt| / (theta phidot) at the slip (listed), plus the start's",
              "nutation: agreement to about that, not to round-off, is what to expect; the numbers are shown as they come.",
              "", "| law | mu | theta (drift) | theta (run) | run/drift - 1 | a(theta) | t (drift, s) | t (run, s) | "
              "mu_req before the switch / at the event | t0 fitted - t (run, s) |", "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
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
    lines += ["", f"The finite-time singularity t0 of the dissipation study: {t0s}. A positive last column: the run slips",
              "before t0."]
    return lines

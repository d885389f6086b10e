"""REPORT.md's section on the reference set, rendered from its index (reports/reference/index.json),
the proved enclosures' index (reports/reference/proved/index.json) and the records of
``reference --check`` at each precision."""
from __future__ import annotations

from ..reference.check import CaseCheck


def render_markdown(index: dict, checks: dict, proved=None) -> list:
    """The report's section on the reference set: the cases, their proofs and ``reference --check``.

    ``checks`` maps a precision name to its list of :class:`CaseCheck` (or their records);
    ``proved`` is the proved enclosures' summary rows (None: none were made).
    """
    recs = {p: [c.to_record() if isinstance(c, CaseCheck) else c for c in cs] for p, cs in checks.items()}
    lines = [
        "",
        "## Reference trajectories",
        "",
        f"`reports/reference/` holds {len(index['cases'])} cases (every model; quiet and wild motions; 1 to 100 s; the "
        "paper's figure runs that stay in their model's domain), each integrated on the derived equations at "
        f"{index['precisions']['low']} and {index['precisions']['high']}; a stored value carries the digits the two runs "
        "agree on and an abs_error estimate (reports/reference/README.md): agreement, not proof. Agreeing digits at t_end: the fewest over the "
        "eight state components (components whose exact value is 0 are agreed zeros, not counted), and the median; "
        "'predicted' is -log10(eps_128 sqrt(N) R Y/|y|) for the component with the fewest, R its row sum of the "
        "state-transition matrix from the variational equations: a conservative estimate, as for the check bound.",
        "",
        "| case | model | kind | source | t_end (s) | steps (128 bits) | agreeing digits at t_end: min (component) "
        "| predicted | median | max row sum at t_end |",
        "|---|---|---|---|---:|---:|---:|---:|---:|---:|",
    ]
    for e in index["cases"]:
        lines.append(f"| {e['name']} | {e['model']} | {e['kind']} | {e['source']} | {e['t_end']} "
                     f"| {e['steps'][index['precisions']['low']]} | {e['min_certified_digits_final']} "
                     f"({e['weakest_component']}) | {e['predicted_digits_weakest']} "
                     f"| {e['median_certified_digits_final']} | {e['max_row_sum_final']:.3g} |")
    coulomb = [e for e in index["cases"] if "switches" in e]
    if coulomb:
        lines += ["", "The Coulomb cases (a coin that rolls and slides, mu = static = kinetic) are runs of the event-driven "
                  "hybrid (verify/engine/hybrid.py) at the same two precisions; their switch times are agreed like any "
                  "value, and their conditioning is measured by central differences of whole quad runs (the variational "
                  "equations know nothing of the switches). They are agreed, not proved: "
                  + "; ".join(f"{e['name']} (mu = {e['mu']}): "
                              + ", ".join(f"{w['kind']} at t = {w['t'][:14]}... ({w['digits']} digits)"
                                          for w in e["switches"]) for e in coulomb) + "."]
    short = [e["min_certified_digits_final"] for e in index["cases"] if float(e["t_end"]) <= 10]
    long_ = [(e["name"], e["min_certified_digits_final"], e["max_row_sum_final"]) for e in index["cases"]
             if float(e["t_end"]) >= 100]
    lines += ["", f"Runs up to 10 s keep at least {min(short)} agreeing digits at t_end; at 100 s "
                  + ", ".join(f"{n} keeps {d} (row sum {r:.2g})" for n, d, r in long_)
                  + ": the flows are integrable, so the transition matrix grows about linearly with time and "
                    "costs about one digit per decade of it.", "",
              *_proved_lines(proved),
              "**`python -m verify reference --check`**: every case re-integrated by the suite at a working precision, "
              "the largest error against the agreed values in units of the bound eps (sqrt(N) R* Y + P + |y|) + "
              "abs_error (verify/reference/check.py), and how much of that bound at the worst point is the reference's "
              "own uncertainty; and the largest distance from a proved ball in units of the same bound without "
              "abs_error.", "",
              "| precision | cases | within bound | largest error / bound | at | median error / bound "
              "| largest proof gap / bound |",
              "|---|---:|---:|---:|---|---:|---:|"]
    for p, cs in recs.items():
        worst = max(cs, key=lambda c: c["ratio"])
        ratios = sorted(c["ratio"] for c in cs)
        gaps = [c["proof_ratio"] for c in cs if c.get("proof_ratio") is not None]
        lines.append(f"| {p} | {len(cs)} | {sum(c['ok'] for c in cs)} | {worst['ratio']:.2e} | {worst['case']}: "
                     f"{worst['where']} | {ratios[len(ratios) // 2]:.2e} | {max(gaps):.2e} ({len(gaps)} cases) |"
                     if gaps else f"| {p} | {len(cs)} | {sum(c['ok'] for c in cs)} | {worst['ratio']:.2e} | "
                     f"{worst['case']}: {worst['where']} | {ratios[len(ratios) // 2]:.2e} | – |")
    lines += ["", "Per case:", "", "| case | " + " | ".join(f"{p}: error / bound" for p in recs) + " |",
              "|---|" + "---:|" * len(recs)]
    names = [c["case"] for c in next(iter(recs.values()))]
    for n in names:
        cells = []
        for p in recs:
            c = next(c for c in recs[p] if c["case"] == n)
            cells.append(f"{c['ratio']:.2e}" + ("" if c["ok"] else " FAIL"))
        lines.append(f"| {n} | " + " | ".join(cells) + " |")
    return lines


def _proved_lines(proved) -> list:
    """The proved enclosures: per case, the most digits proved at 1 s and at its end, beside the agreed ones."""
    if not proved:
        return []
    by_case = {}
    for row in proved:
        by_case.setdefault(row["case"], []).append(row)

    def best(rows, key):
        """(digits, bits) of the proof with the most digits at ``key`` ('at_1s' or 'at_last' of a complete one)."""
        found = [(r[key]["proved_digits_fewest"], r["bits"]) for r in rows
                 if r[key] and r[key]["proved_digits_fewest"] is not None and (key == "at_1s" or r["complete"])]
        return max(found, default=None)

    lines = ["**Proved enclosures** (`python -m verify reference --prove`, reports/reference/proved/): balls that "
             "contain the exact solution of each case's equations from its exact start (verify/proof: a validated "
             "Taylor integrator in Arb ball arithmetic), at 128 bits to each case's end, at 256 bits to 1 s, and at "
             "192 bits to the end where 128 bits proved fewer than 30 digits there. Digits: proved significant digits "
             "(bits of the proof) / agreed digits, the fewest over the components that are not agreed zeros. "
             "'Contradicted' counts stored values whose claim |value - exact| <= abs_error a proof refutes.", "",
             "| case | t_end (s) | digits at 1 s | digits at t_end | contradicted |", "|---|---:|---|---|---:|"]
    for case, rows in by_case.items():
        cells = []
        for key in ("at_1s", "at_last"):
            found = best(rows, key)
            agreed = next((r[key]["agreed_digits_fewest"] for r in rows if r[key]), None)
            reached = max(rows, key=lambda r: float(r["t_proved"]))
            cells.append(f"{found[0]:.1f} ({found[1]}) / {agreed}" if found else
                         f"proved to {reached['t_proved']} s only")
        lines.append(f"| {case} | {rows[0]['t_end']} | {cells[0]} | {cells[1]} | "
                     f"{sum(r['claims_contradicted'] for r in rows)} |")
    return lines + [""]

"""The report's Engines section, rendered from ``reports/engines.json`` (written by ``make engines``).

The report never runs an engine: it shows the latest board (:mod:`verify.leaderboard`) with its date of
sources, or says how to make one.  Per case: every engine and setting with the fewest digits over the run
and where, the final digits, the energy drift, the contact's height and slip errors, the wall time and a
verdict in words, beside this suite's own double and quad runs for scale.  A Coulomb case (friction mu, the
body rolls and slides) shows the energy error against the reference's energy (friction takes energy: a drift
is no error there), the slip speed error, and where each run slides against the reference's switches.
"""
from __future__ import annotations

from typing import Optional

from ..leaderboard import words


def _num(value, fmt: str) -> str:
    return "-" if value is None else format(value, fmt)


def render_markdown(board: Optional[dict]) -> list:
    lines = ["## Engines", ""]
    if board is None:
        return lines + ["No engine board yet: `make engines` runs the adapters of `examples/engines/` (Exudyn, MuJoCo, "
                        "PyBullet, Drake) on the reference cases and writes `reports/engines.json`, which this "
                        "section shows.", ""]
    commit = (board.get("sources") or {}).get("commit") or "unknown"
    lines += [f"Other physics engines on the reference cases, each at its defaults and at the best settings its "
              f"adapter found (`examples/engines/*_adapter.py`: settings and pitfalls in each docstring), scored "
              f"like any run (`python -m verify score`): digits of agreement with the proved reference over the run "
              f"(the fewest, and at the end), the energy drift, the contact point's height and slip (form (b)), wall "
              f"time on {board.get('machine', 'this machine')} (sources at {commit[:12]}). This suite's own runs "
              "(heyoka, double and quad, at the precision's epsilon) are given for scale. Made by `make engines`; "
              "the report does not re-run them.", "",
              "![Fewest digits of agreement against wall time for every engine and setting on each case "
              "(log time).](figures/engines.png)", ""]
    for case in board["cases"]:
        rows = [r for r in board["rows"] if r["case"] == case["case"]]
        span = "" if case["t_end_run"] is None else f" (first {case['t_end_run']:g} s)"
        coulomb = case.get("coulomb") or next((r["friction"] for r in rows if r.get("friction")), None)
        if coulomb:
            lines += _coulomb_table(case, coulomb, rows, span)
            continue
        lines += [f"**{case['case']}**{span}", "",
                  "| engine | setting | fewest digits (where) | final digits | energy drift | contact height / slip "
                  "| wall s | verdict |", "|---|---|---|---:|---:|---:|---:|---|"]
        for r in rows:
            s = r.get("score") or {}
            final = min((c["final_digits"] for c in s.get("components", {}).values()), default=None)
            where = f" ({s['worst']})" if s.get("worst") else ""
            lines.append(f"| {r.get('engine', r['adapter'])} {r.get('version', '')} | {r['setting']} | "
                         f"{_num(s.get('min_digits'), '.2f')}{where} | {_num(final, '.2f')} | "
                         f"{_num(s.get('energy_rel_drift'), '.1e')} | {_num(s.get('contact_height'), '.1e')} / "
                         f"{_num(s.get('contact_velocity'), '.1e')} | {_num(r.get('wall_s'), '.3g')} | {words(r)} |")
        lines.append("")
    return lines


def _slides(friction) -> str:
    """The run's slides as 'a-b, c-d' (4 decimals; '...' after three, 'none')."""
    run = (friction or {}).get("run") or {}
    slides = run.get("slides")
    if slides is None:
        return "-"
    if not slides:
        return "none"
    text = ", ".join(f"{a:.4f} to {'end' if b is None else format(b, '.4f')}" for a, b in slides[:3])
    return text + (f" (+{run['n_slides'] - 3} more)" if run.get("n_slides", 0) > 3 else "")


def _coulomb_table(case: dict, coulomb: dict, rows: list, span: str) -> list:
    mu = coulomb.get("mu")
    skid = coulomb.get("velocity")
    start = (f"starts sliding (C's velocity ({float(skid[0]):.4g}, {float(skid[1]):.4g}))" if skid
             else "starts rolling")
    lines = [f"**{case['case']}**{span}: Coulomb friction mu = {mu}, {start}; slides = where the run's contact slip "
             "speed exceeds 0.1 R/s (the suite's rows: its event-located phases)", "",
             "| engine | setting | fewest digits (where) | final digits | energy error | slip speed error "
             "| contact height | slides | wall s | verdict |", "|---|---|---|---:|---:|---:|---:|---|---:|---|"]
    for r in rows:
        s = r.get("score") or {}
        final = min((c["final_digits"] for c in s.get("components", {}).values()), default=None)
        where = f" ({s['worst']})" if s.get("worst") else ""
        lines.append(f"| {r.get('engine', r['adapter'])} {r.get('version', '')} | {r['setting']} | "
                     f"{_num(s.get('min_digits'), '.2f')}{where} | {_num(final, '.2f')} | "
                     f"{_num(s.get('energy_rel_error'), '.1e')} | {_num(s.get('slip_speed_error'), '.1e')} | "
                     f"{_num(s.get('contact_height'), '.1e')} | {_slides(r.get('friction'))} | "
                     f"{_num(r.get('wall_s'), '.3g')} | {words(r)} |")
    return lines + [""]

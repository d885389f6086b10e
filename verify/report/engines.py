"""The report's Engines section, rendered from ``reports/engines.json`` (written by ``make engines``).

The report never runs an engine: it shows the latest board (:mod:`verify.leaderboard`) with its date of
sources, or says how to make one.  Per case: every engine and setting with the fewest digits over the run
and where, the final digits, the energy drift, the contact's height and slip errors, the wall time and a
verdict in words, beside this suite's own double and quad runs for scale.
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

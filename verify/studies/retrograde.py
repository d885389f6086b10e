"""The rolling ring's retrograde turn (issue 6): which dissipative term reproduces it, for which bodies.

The paper ends (Figs. 9, 12 and the text after them) on the observation that spinning rings,
unlike disks, end up orbiting against their spin, and on two competing explanations: air drag
tuned by the hole (Jalali, Sarebangholi & Alam) and rolling friction (Borisov, Kilin &
Karavaev).  Both are model terms in :mod:`models.ring_dissipation`; the shipped sweeps
``verify/sweep/specs/ring-retrograde-*.toml`` map, over the ring's shape (half-thickness h and
wall w, from a flat disk to the paper's ring) and the coefficient c, whether a body spun like a
coin turns retrograde before it falls flat.  A conservative control (c = 0, same starts, same
duration) runs beside them.

The observation is "rings reverse, disks do not"; the verdict for a mechanism is read off the
corners of the map: a flat disk (h = 0.01, w = 1), a flat ring (h = 0.01, w = 0.1366), a thick
disk (h = 0.4344, w = 1) and the paper's ring (h = 0.4344, w = 0.1366).
"""
from __future__ import annotations

import math
import sys
import tempfile
from pathlib import Path

from ..sweep import SPECS, load, parse, run_sweep
from ..sweep.plot import render
from ..sweep.store import Store

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

MECHANISMS = ("air-drag", "rolling-friction")
BODIES = (("flat disk", 0.01, 1.0), ("flat ring", 0.01, 0.1366), ("thick disk", 0.4344, 1.0),
          ("paper's ring", 0.4344, 0.1366))


def spec_path(mechanism: str) -> Path:
    return SPECS / f"ring-retrograde-{mechanism}.toml"


def control_text(mechanism: str) -> str:
    """The mechanism's spec with c = 0 (the conservative ring) instead of the c axis."""
    data = tomllib.loads(spec_path(mechanism).read_text())
    data["sweep"]["name"] += "-control"
    data["axis"] = [a for a in data["axis"] if a["name"] != "c"]
    data.setdefault("params", {})["c"] = 0.0
    data["plot"].pop("panels", None)
    data["plot"]["title"] = f"ring+{mechanism} with c = 0 (conservative control)"
    return dumps_toml(data)


def dumps_toml(data: dict) -> str:
    """TOML for the flat layout of a sweep spec (tables of scalars and lists, an array of [[axis]])."""
    def value(v):
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, str):
            return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return repr(v)

    out = []
    for key, table in data.items():
        rows = table if isinstance(table, list) else [table]
        for row in rows:
            out.append(f"[[{key}]]" if isinstance(table, list) else f"[{key}]")
            out += [f"{k} = {value(v)}" for k, v in row.items()]
            out.append("")
    return "\n".join(out)


def run_study(directory=None, threads=None, progress=None) -> dict:
    """Run both mechanisms and the controls (stores in ``directory``, a temporary folder by default)."""
    say = progress or (lambda s: None)
    owned = None
    if directory is None:
        owned = tempfile.TemporaryDirectory(prefix="retrograde-")
        directory = owned.name
    try:
        out = {}
        for m in MECHANISMS:
            spec = load(spec_path(m), store=str(Path(directory) / f"{m}.sqlite"))
            control = parse(control_text(m), f"{m} control", store=str(Path(directory) / f"{m}-control.sqlite"))
            results = {}
            for label, s in (("sweep", spec), ("control", control)):
                say(f"  retrograde turn: {s.name} ({s.n_points} trajectories)")
                res = run_sweep(s, threads=threads, progress=False)
                with Store(s) as store:
                    results[label] = (s, store.rows(), res.seconds)
            out[m] = summarise(m, results)
        return out
    finally:
        if owned is not None:
            owned.cleanup()


def _at(rows: list, h: float, w: float, c=None) -> dict:
    def close(a, b):
        return abs(a - b) <= 1e-9 * max(1.0, abs(b))

    for r in rows:
        if close(r["in_h"], h) and close(r["in_w"], w) and (c is None or close(r["in_c"], c)):
            return r
    raise KeyError((h, w, c))


def _yes(v) -> bool:
    return v is not None and not (isinstance(v, float) and math.isnan(v)) and v > 0.5


def summarise(mechanism: str, results: dict) -> dict:
    spec, rows, seconds = results["sweep"]
    cspec, crows, cseconds = results["control"]
    cs = next(a.values for a in spec.axes if a.name == "c")
    judged = [r for r in rows if r["retrograde_turn"] is not None]
    per_c = []
    for c in cs:
        sel = [r for r in judged if abs(r["in_c"] - c) <= 1e-12 * c]
        per_c.append({"c": f"{c:.4g}", "judged": len(sel), "retrograde_turn": sum(_yes(r["retrograde_turn"]) for r in sel),
                      "roll_reversal": sum(_yes(r["roll_reversal"]) for r in sel),
                      "fell_flat": sum(r["outcome"] == "theta_stop" for r in sel)})
    bodies = []
    for name, h, w in BODIES:
        for c in cs:
            r = _at(rows, h, w, c)
            bodies.append({"body": name, "h": h, "w": w, "c": f"{c:.4g}", "outcome": r["outcome"],
                           "t_stop": round(r["t_stop"], 2), "retrograde_turn": _yes(r["retrograde_turn"]),
                           "t_retrograde": None if not _yes(r["retrograde_turn"]) else round(r["t_retrograde"], 2),
                           "orbit": [r["orbit_start"], r["orbit_end"]], "spin": [r["spin_start"], r["spin_end"]],
                           "roll_reversal": _yes(r["roll_reversal"]), "energy_drift": f"{r['energy_drift']:.1e}"})
    # judged where both fell flat (theta < theta_stop) within t_end: "before the ring falls flat"
    fell = {b["c"] for b in bodies if b["body"] == "paper's ring" and b["outcome"] == "theta_stop"} & \
        {b["c"] for b in bodies if b["body"] == "flat disk" and b["outcome"] == "theta_stop"}
    ring_turns = [b["retrograde_turn"] for b in bodies if b["body"] == "paper's ring" and b["c"] in fell]
    disk_turns = [b["retrograde_turn"] for b in bodies if b["body"] == "flat disk" and b["c"] in fell]
    control_turns = sum(_yes(r["retrograde_turn"]) for r in crows)
    reproduces = bool(fell) and all(ring_turns) and not any(disk_turns)
    by_axis = {}
    for axis in ("h", "w"):
        values = next(a.values for a in spec.axes if a.name == axis)
        by_axis[axis] = [{axis: round(v, 4), "judged": sum(1 for r in judged if abs(r[f"in_{axis}"] - v) < 1e-12),
                          "turned": sum(_yes(r["retrograde_turn"]) for r in judged if abs(r[f"in_{axis}"] - v) < 1e-12)}
                         for v in values]
    turned = [r for r in judged if _yes(r["retrograde_turn"])]
    by_spin = sum(r["spin_start"] != r["spin_end"] and r["orbit_start"] == r["orbit_end"] for r in turned)
    by_orbit = sum(r["orbit_start"] != r["orbit_end"] and r["spin_start"] == r["spin_end"] for r in turned)
    return {
        "mechanism": mechanism, "spec": f"verify/sweep/specs/{spec_path(mechanism).name}", "trajectories": len(rows),
        "turns": len(turned), "turns_by_spin_reversal": by_spin, "turns_by_orbit_reversal": by_orbit,
        "by_h": by_axis["h"], "by_w": by_axis["w"],
        "per_c": per_c, "bodies": bodies, "control_trajectories": len(crows), "control_retrograde": control_turns,
        "control_fell_flat": sum(r["outcome"] == "theta_stop" for r in crows),
        "max_energy_drift": f"{max(r['energy_drift'] for r in rows + crows):.1e}",
        "reproduces_observation": reproduces,
        "verdict": _verdict(mechanism, reproduces, ring_turns, disk_turns, control_turns),
        "seconds": round(seconds + cseconds, 1),
        "figure": render(spec, rows), "figure_roll": render(_with_plot(spec, "roll_reversal"), rows,
                                                           title=f"ring+{mechanism}: rolling direction reversed (1 = yes)"),
    }


def _with_plot(spec, quantity: str):
    from dataclasses import replace

    return replace(spec, plot={**spec.plot, "quantity": quantity})


def _verdict(mechanism, reproduces, ring_turns, disk_turns, control_turns) -> str:
    if not ring_turns:
        return f"{mechanism}: neither the paper's ring nor a flat disk fell flat within t_end at the same c: not judged"
    ring = "turns retrograde" if all(ring_turns) else ("turns retrograde at some c" if any(ring_turns) else "does not turn")
    disk = "turns retrograde too" if all(disk_turns) else ("turns at some c" if any(disk_turns) else "does not turn")
    text = (f"{mechanism}: the paper's ring {ring}, a flat disk {disk}; "
            f"{'reproduces' if reproduces else 'does not reproduce'} 'rings reverse, disks do not'")
    if control_turns:
        text += f" (caution: {control_turns} conservative control runs turn as well)"
    return text


def render_markdown(study: dict) -> list:
    """The report's section on the retrograde turn (figures named retrograde-<mechanism>[-roll].png)."""
    lines = [
        "",
        "## The ring's retrograde turn (issue 6)",
        "",
        "Both explanations the paper cites are explicit model terms (models/ring_dissipation.py): **air drag** tuned by",
        "the hole (Jalali et al.: tau = -c A(w) |omega_perp| omega_perp, A(w) = 1 - (1 - w)^5 the rocking drag of an",
        "annulus relative to a disk) and **viscous rolling friction** (Borisov et al.: tau = -c (omega - (omega.Z) Z)).",
        "Neither paper's own force laws were available to us; these are the simplest terms with each paper's stated",
        "property. The sweeps (verify/sweep/specs/ring-retrograde-*.toml, run by `python -m verify sweep`) start every",
        "body as a coin is spun -- theta0 = 1.2, phidot0 = 40 s^-1, psidot0 = 0 -- over its shape (half-thickness h and",
        "wall w in units of R, I1 and I3 of an annular cylinder; a flat disk is h = 0.01, w = 1, the paper's ring",
        "h = 0.4344, w = 0.1366) and the coefficient c, until theta < 0.1 (flat) or 120 s. A run turns retrograde when",
        "its orbit (the net turn of the line of nodes over a twentieth of the run; the CM's mean path circles in that",
        "sense) starts in the sense of its spin omega.Z and ends against it. Also recorded: whether the direction in",
        "which the CM rolls along e1 -- hence the centripetal friction force, Jalali et al.'s stated signature -- has",
        "reversed. The conservative control (c = 0) runs the same starts for the same time.",
        "",
        "| mechanism | c | runs judged | retrograde turn | rolling direction reversed | fell flat |",
        "|---|---:|---:|---:|---:|---:|",
    ]
    for m, s in study.items():
        for pc in s["per_c"]:
            lines.append(f"| {m} | {pc['c']} | {pc['judged']} | {pc['retrograde_turn']} | {pc['roll_reversal']} "
                         f"| {pc['fell_flat']} |")
        lines.append(f"| {m}, control c = 0 | 0 | {s['control_trajectories']} | {s['control_retrograde']} | - "
                     f"| {s['control_fell_flat']} |")
    lines += ["", "Retrograde turns by thickness h and by wall w (runs judged, over the other axis and both c):", "",
              "| mechanism | " + " | ".join(f"h = {x['h']}" for x in next(iter(study.values()))["by_h"]) + " | "
              + " | ".join(f"w = {x['w']}" for x in next(iter(study.values()))["by_w"]) + " |",
              "|---|" + "---:|" * (len(next(iter(study.values()))["by_h"]) + len(next(iter(study.values()))["by_w"]))]
    for m, s in study.items():
        lines.append(f"| {m} | " + " | ".join(f"{x['turned']}/{x['judged']}" for x in s["by_h"] + s["by_w"]) + " |")
    lines += ["", "The corners of the maps:", "",
              "| mechanism | body | h | w | c | outcome | t_stop (s) | orbit start/end | spin start/end | retrograde "
              "(at t) | rolling reversed |", "|---|---|---:|---:|---:|---|---:|---|---|---|---|"]
    for m, s in study.items():
        for b in s["bodies"]:
            lines.append(f"| {m} | {b['body']} | {b['h']} | {b['w']} | {b['c']} | {b['outcome']} | {b['t_stop']} "
                         f"| {_sign(b['orbit'])} | {_sign(b['spin'])} | "
                         f"{'yes (' + str(b['t_retrograde']) + ' s)' if b['retrograde_turn'] else 'no'} "
                         f"| {'yes' if b['roll_reversal'] else 'no'} |")
    how = "; ".join(f"{m}: {s['turns_by_spin_reversal']} of its {s['turns']} retrograde turns are the spin omega.Z "
                    f"reversing while the orbit keeps its sense, {s['turns_by_orbit_reversal']} the orbit reversing"
                    for m, s in study.items())
    lines += ["", "**Verdict.** " + " ".join(s["verdict"] + "." for s in study.values()),
              f"How the runs end up retrograde -- {how}. Runs that fall flat within a few tenths of a second are "
              "judged on windows too short to hold a nutation, which is why the spread of c matters more than any "
              "single point.",
              f"Energy: E + W = E(0) along every run to {max(float(s['max_energy_drift']) for s in study.values()):.0e} "
              "of the energy's scale.", ""]
    for m in study:
        lines += [f"![](figures/retrograde-{m}.png)", "", f"![](figures/retrograde-{m}-roll.png)", ""]
    return lines


def _sign(pair) -> str:
    return "/".join("-" if v is None or (isinstance(v, float) and math.isnan(v)) else ("+" if v > 0 else "-" if v < 0
                                                                                        else "0") for v in pair)

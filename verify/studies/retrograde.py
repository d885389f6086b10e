"""The rolling ring's retrograde turn: which dissipative term reproduces it, for which bodies.

The paper ends (Figs. 9, 12 and the text after them) on the observation that spinning rings,
unlike disks, end up orbiting against their spin ("the end state motion (say clockwise) will be
preceded by a counter-clockwise phase"), and on two competing explanations: air drag tuned by
the hole (Jalali, Sarebangholi & Alam) and rolling friction (Borisov, Kilin & Karavaev).  Both
are model terms in :mod:`models.ring_dissipation`; the shipped sweeps
``verify/sweep/specs/ring-retrograde-*.toml`` map, over the ring's shape (half-thickness h and
wall w, from a flat disk to the paper's ring) and the coefficient c, whether a body spun like a
coin turns retrograde before it falls flat.  A conservative control (c = 0, same starts, same
duration) runs beside them.

"Orbit" is the sense in which the centre of mass circles over many nutation loops -- its slow
path, read in windows of 12 nutations by the two filters of :mod:`verify.circling` and
undecided wherever they do not agree (:func:`verify.studies.orbits.senses`).  A run turns
retrograde when its slow path starts in the sense of its spin omega.Z and ends against it, in
the first and last windows that decide; it is undecided when fewer than two windows decide.
The former reading -- the net turn of the line of nodes, which counts the loops -- is shown
beside it for comparison only.

The observation is "rings reverse, disks do not"; the verdict for a mechanism is read off the
corners of the map: a flat disk (h = 0.01, w = 1), a flat ring (h = 0.01, w = 0.1366), a thick
disk (h = 0.4344, w = 1) and the paper's ring (h = 0.4344, w = 0.1366).
"""
from __future__ import annotations

import math
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

from ..sweep import SPECS, load, parse, run_sweep
from ..sweep.store import Store
from .orbits import senses

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


@dataclass(frozen=True)
class Study:
    """What :func:`run_study` found: the summaries (JSON-ready) and the sweeps they summarise."""

    summaries: dict  # mechanism -> summarise(mechanism, ...)
    sweeps: dict  # mechanism -> (spec, rows) of the mechanism's sweep (not the control), for its figures


def run_study(directory=None, threads=None, progress=None, mechanisms=MECHANISMS) -> Study:
    """Run the mechanisms (both by default) and their controls (stores in ``directory``, a temporary folder by default)."""
    say = progress or (lambda s: None)
    owned = None
    if directory is None:
        owned = tempfile.TemporaryDirectory(prefix="retrograde-")
        directory = owned.name
    try:
        out, sweeps = {}, {}
        for m in mechanisms:
            spec = load(spec_path(m), store=str(Path(directory) / f"{m}.sqlite"))
            control = parse(control_text(m), f"{m} control", store=str(Path(directory) / f"{m}-control.sqlite"))
            results = {}
            for label, s in (("sweep", spec), ("control", control)):
                say(f"  retrograde turn: {s.name} ({s.n_points} trajectories)")
                res = run_sweep(s, threads=threads, progress=False, senses=senses)
                with Store(s) as store:
                    results[label] = (s, store.rows(), res.seconds)
            out[m] = summarise(m, results)
            sweeps[m] = results["sweep"][:2]
        return Study(out, sweeps)
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


def _nan(v) -> bool:
    return v is None or (isinstance(v, float) and math.isnan(v))


def _yes(v) -> bool:
    return not _nan(v) and v > 0.5


def _tally(rows: list) -> dict:
    """Counts of the slow-path reading over ``rows``."""
    return {"runs": len(rows), "judged": sum(not _nan(r["retrograde_turn"]) for r in rows),
            "turned": sum(_yes(r["retrograde_turn"]) for r in rows),
            "undecided": sum(_nan(r["retrograde_turn"]) for r in rows),
            "too_short": sum(_nan(r["windows"]) for r in rows),
            "read_judged": sum(not _nan(r["retrograde_by_last_read"]) for r in rows),
            "read_turned": sum(_yes(r["retrograde_by_last_read"]) for r in rows),
            "orbit_reversal": sum(_yes(r["orbit_reversal"]) for r in rows),
            "end_read": sum(not _nan(r["orbit_last"]) and r["orbit_last"] != 0 for r in rows),
            "node_turn": sum(_yes(r["node_retrograde_turn"]) for r in rows),
            "roll_reversal": sum(_yes(r["roll_reversal"]) for r in rows),
            "fell_flat": sum(r["outcome"] == "theta_stop" for r in rows)}


def _state(v) -> str:
    return "undecided" if _nan(v) else ("turns" if v > 0.5 else "does not turn")


def _round(v, digits=2):
    return None if _nan(v) else round(v, digits)


def summarise(mechanism: str, results: dict) -> dict:
    spec, rows, seconds = results["sweep"]
    cspec, crows, cseconds = results["control"]
    cs = next(a.values for a in spec.axes if a.name == "c")
    per_c = []
    for c in cs:
        sel = [r for r in rows if abs(r["in_c"] - c) <= 1e-12 * c]
        per_c.append({"c": f"{c:.4g}", **_tally(sel)})
    bodies = []
    for name, h, w in BODIES:
        for c in cs:
            r = _at(rows, h, w, c)
            bodies.append({"body": name, "h": h, "w": w, "c": f"{c:.4g}", "outcome": r["outcome"],
                           "t_stop": round(r["t_stop"], 2), "retrograde_turn": _state(r["retrograde_turn"]),
                           "retrograde_by_last_read": _state(r["retrograde_by_last_read"]),
                           "t_retrograde": _round(r["t_retrograde"]),
                           "windows": None if _nan(r["windows"]) else int(r["windows"]),
                           "windows_undecided": None if _nan(r["windows_undecided"]) else int(r["windows_undecided"]),
                           "orbit": [r["orbit_start"], r["orbit_end"]],
                           "t_orbit": [_round(r["t_orbit_start"]), _round(r["t_orbit_end"])],
                           "orbit_last": r["orbit_last"], "spin": [r["spin_start"], r["spin_end"]],
                           "orbit_reversal": "undecided" if _nan(r["orbit_reversal"]) else
                           ("yes" if r["orbit_reversal"] > 0.5 else "no"),
                           "last_window_turns": [_round(r["strobe_last"]), _round(r["mean_last"])],
                           "node_turn": [r["node_turn_start"], r["node_turn_end"]],
                           "node_retrograde_turn": _yes(r["node_retrograde_turn"]),
                           "roll_reversal": _yes(r["roll_reversal"]), "energy_drift_vs_terms": f"{r['energy_drift_vs_terms']:.1e}"})
    # judged where both fell flat (theta < theta_stop) within t_end: "before the ring falls flat"
    fell = {b["c"] for b in bodies if b["body"] == "paper's ring" and b["outcome"] == "theta_stop"} & \
        {b["c"] for b in bodies if b["body"] == "flat disk" and b["outcome"] == "theta_stop"}
    ring = [b["retrograde_turn"] for b in bodies if b["body"] == "paper's ring" and b["c"] in fell]
    disk = [b["retrograde_turn"] for b in bodies if b["body"] == "flat disk" and b["c"] in fell]
    ring_read = [b["retrograde_by_last_read"] for b in bodies if b["body"] == "paper's ring" and b["c"] in fell]
    disk_read = [b["retrograde_by_last_read"] for b in bodies if b["body"] == "flat disk" and b["c"] in fell]
    control = _tally(crows)
    if not fell:
        reproduces = None
    elif "does not turn" in ring or "turns" in disk:
        reproduces = False
    elif "undecided" in ring or "undecided" in disk:
        reproduces = None
    else:
        reproduces = True
    by_axis = {}
    for axis in ("h", "w"):
        values = next(a.values for a in spec.axes if a.name == axis)
        by_axis[axis] = [{axis: round(v, 4), **_tally([r for r in rows if abs(r[f"in_{axis}"] - v) < 1e-12])}
                         for v in values]
    turned = [r for r in rows if _yes(r["retrograde_by_last_read"])]
    # how a turn (as far as read) comes about: the orbit reversing, or the spin reversing under the orbit
    by_spin = sum(r["spin_start"] != r["spin_end"] and r["orbit_start"] == r["orbit_end"] for r in turned)
    by_orbit = sum(r["orbit_start"] != r["orbit_end"] for r in turned)
    resolution = [r["points_per_nutation"] for r in rows + crows if not _nan(r["points_per_nutation"])]
    return {
        "mechanism": mechanism, "spec": f"verify/sweep/specs/{spec_path(mechanism).name}", "trajectories": len(rows),
        **_tally(rows), "turns_by_spin_reversal": by_spin, "turns_by_orbit_reversal": by_orbit,
        "windows": int(sum(r["windows"] for r in rows if not _nan(r["windows"]))),
        "windows_undecided": int(sum(r["windows_undecided"] for r in rows if not _nan(r["windows_undecided"]))),
        "by_h": by_axis["h"], "by_w": by_axis["w"], "per_c": per_c, "bodies": bodies,
        "control": control, "control_windows": int(sum(r["windows"] for r in crows if not _nan(r["windows"]))),
        "control_windows_undecided": int(sum(r["windows_undecided"] for r in crows
                                             if not _nan(r["windows_undecided"]))),
        "min_points_per_nutation": round(min(resolution), 1) if resolution else None,
        "max_energy_drift_vs_terms": f"{max(r['energy_drift_vs_terms'] for r in rows + crows):.1e}",
        "reproduces_observation": reproduces,
        "verdict": _verdict(mechanism, reproduces, ring, disk, control, ring_read, disk_read),
        "seconds": round(seconds + cseconds, 1),
    }


def _verdict(mechanism, reproduces, ring: list, disk: list, control: dict, ring_read=(), disk_read=()) -> str:
    """One sentence per mechanism from the slow-path reading of the paper's ring and the flat disk."""
    if not ring:
        return f"{mechanism}: neither the paper's ring nor a flat disk fell flat within t_end at the same c: not judged"

    def say(states, body):
        if len(set(states)) == 1:
            return f"{body} {states[0]}"
        return f"{body}: " + ", ".join(f"{states.count(s)} of {len(states)} c {s}"
                                      for s in ("turns", "does not turn", "undecided") if s in states)

    outcome = {True: "reproduces", False: "does not reproduce",
               None: "cannot say whether it reproduces"}[reproduces]
    text = (f"{mechanism}: {say(list(ring), 'the paper' + chr(39) + 's ring')}, {say(list(disk), 'a flat disk')} "
            f"(slow path, end state read); {outcome} 'rings reverse, disks do not'")
    if ring_read and (list(ring_read) != list(ring) or list(disk_read) != list(disk)):
        text += (f" -- as far as the slow path can be read, {say(list(ring_read), 'the paper' + chr(39) + 's ring')}, "
                 f"{say(list(disk_read), 'a flat disk')}")
    if control["turned"] or control["read_turned"]:
        text += (f" (caution: {max(control['turned'], control['read_turned'])} conservative control runs turn "
                 "as well)")
    return text

"""REPORT.md's section on the ring's retrograde turn and its figures, rendered from what
:func:`verify.studies.retrograde.run_study` found: the summaries (results.json's ``studies.retrograde``)
and each mechanism's sweep (figures retrograde-<mechanism>.png and retrograde-<mechanism>-roll.png:
one cell per run, yes/no, with the runs that are not read labelled as such)."""
from __future__ import annotations

import math

import matplotlib
import numpy as np
from matplotlib.colors import BoundaryNorm, ListedColormap
from matplotlib.patches import Patch

from .. import style
from .figures import Image
from ..style import png_bytes

#: the cells of a yes/no map: (code, colour, legend text); NaN cells are told apart by whether
#: the run had windows to read (verify/sweep/engine.py, senses: every value is NaN without them)
CATEGORIES = ((1, style.YES, "yes"), (0, style.NO, "no"),
              (2, style.UNDECIDED, "undecided: its end state (or its start) is not read"),
              (3, style.TOO_SHORT, "too short: fewer than 2 windows of 12 nutations"))
QUANTITIES = {"retrograde_turn": "slow-path retrograde turn before theta < 0.1",
              "roll_reversal": "rolling direction reversed"}


def figures(mechanism: str, spec, rows: list) -> dict:
    """The two maps of one mechanism's sweep, file name -> :class:`.figures.Image`: the retrograde
    turn (the spec's own [plot] axes) and the rolling direction reversed."""
    out = {}
    for quantity, name in (("retrograde_turn", f"retrograde-{mechanism}.png"),
                           ("roll_reversal", f"retrograde-{mechanism}-roll.png")):
        with matplotlib.rc_context(style.RC):
            data = png_bytes(draw_yes_no(spec, rows, quantity))
        out[name] = Image(name, data, yes_no_alt_text(spec, rows, quantity))
    return out


def categorise(spec, rows: list, quantity: str):
    """(x values, y values, panel values, codes (panel, y, x)) of ``quantity`` read as yes/no.

    Codes as :data:`CATEGORIES`: 1 yes (> 0.5), 0 no, 2 NaN on a run that had windows to read,
    3 NaN on a run too short to have any; -1 where no run is stored (none in a complete sweep).
    """
    x, y, panels = spec.plot["x"], spec.plot["y"], spec.plot["panels"]
    xs, ys, ps = (np.array(next(a.values for a in spec.axes if a.name == n)) for n in (x, y, panels))
    codes = np.full((len(ps), len(ys), len(xs)), -1, dtype=int)
    for r in rows:
        v = r[quantity]
        code = (3 if _nan(r["windows"]) else 2) if _nan(v) else int(v > 0.5)
        codes[_index(ps, r[f"in_{panels}"]), _index(ys, r[f"in_{y}"]), _index(xs, r[f"in_{x}"])] = code
    return xs, ys, ps, codes


def draw_yes_no(spec, rows: list, quantity: str):
    """One panel per value of the spec's ``panels`` axis (c): each run's yes/no as a cell over the
    spec's x (w) and y (h) axes, four labelled categories in a legend, the counts in it."""
    xs, ys, ps, codes = categorise(spec, rows, quantity)
    if (codes < 0).any():
        raise ValueError(f"{spec.name}: {int((codes < 0).sum())} points of the grid have no run stored")
    mechanism = spec.model.removeprefix("ring+")
    fig, axes = style.figure(height=4.6, ncols=len(ps), squeeze=False)
    cmap = ListedColormap([colour for _, colour, _ in sorted(CATEGORIES)])
    norm = BoundaryNorm(np.arange(-0.5, len(CATEGORIES)), cmap.N)
    for ax, c, panel in zip(axes[0], ps, codes):
        ax.grid(False)
        ax.pcolormesh(xs, ys, panel, shading="nearest", cmap=cmap, norm=norm, edgecolors="white", linewidth=0.5)
        ax.set_title(f"{spec.plot['panels']} = {c:.4g}")
        ax.set_xlabel(f"{spec.plot['x']} / R")
        ax.set_ylabel(f"{spec.plot['y']} / R")
        ax.set_xticks(xs, [f"{v:.3g}" for v in xs])
        ax.set_yticks(ys, [f"{v:.3g}" for v in ys])
    handles = [Patch(facecolor=colour, edgecolor="0.5", label=f"{text} ({int((codes == code).sum())})")
               for code, colour, text in CATEGORIES]
    fig.legend(handles=handles, loc="outside lower center", ncols=2, title="runs (count over both panels)")
    fig.suptitle(f"ring+{mechanism}: {QUANTITIES[quantity]} (wall w and half-thickness h in units of the radius R)")
    return fig


def yes_no_alt_text(spec, rows: list, quantity: str) -> str:
    """What :func:`draw_yes_no` shows: the axes and ranges, the counts of each category per panel."""
    xs, ys, ps, codes = categorise(spec, rows, quantity)
    x, y, panels = spec.plot["x"], spec.plot["y"], spec.plot["panels"]
    counts = "; ".join(f"{panels} = {c:.4g}: " + ", ".join(f"{int((panel == code).sum())} {text.split(':')[0]}"
                                                            for code, _, text in CATEGORIES)
                       for c, panel in zip(ps, codes))
    return (f"{spec.model}: {QUANTITIES[quantity]} (yes, no, undecided or too short) for each run over "
            f"{x} from {xs.min():g} to {xs.max():g} R and {y} from {ys.min():g} to {ys.max():g} R, one panel per "
            f"{panels}. {counts}.")


def _index(values, v) -> int:
    return int(np.argmin(np.abs(values - v)))


def _nan(v) -> bool:
    return v is None or (isinstance(v, float) and math.isnan(v))


def render_markdown(study: dict) -> list:
    """The report's section on the retrograde turn (figures named retrograde-<mechanism>[-roll].png)."""
    first = next(iter(study.values()))
    ppn = [s["min_points_per_nutation"] for s in study.values() if s["min_points_per_nutation"]]
    lines = [
        "",
        "## The ring's retrograde turn: air drag or rolling friction",
        "",
        "Both explanations the paper cites are explicit model terms (models/ring_dissipation.py): **air drag** tuned by",
        "the hole (Jalali et al.: tau = -c A(w) |omega_perp| omega_perp, A(w) = 1 - (1 - w)^5 the rocking drag of an",
        "annulus relative to a disk) and **viscous rolling friction** (Borisov et al.: tau = -c (omega - (omega.Z) Z)).",
        "Neither paper's own force laws were available to us; these are the simplest terms with each paper's stated",
        "property. The sweeps (verify/sweep/specs/ring-retrograde-*.toml, run by `python -m verify sweep`) start every",
        "body as a coin is spun -- theta0 = 1.2, phidot0 = 40 s^-1, psidot0 = 0 -- over its shape (half-thickness h and",
        "wall w in units of R, I1 and I3 of an annular cylinder; a flat disk is h = 0.01, w = 1, the paper's ring",
        "h = 0.4344, w = 0.1366) and the coefficient c, until theta < 0.1 (flat) or 120 s. The conservative control",
        "(c = 0) runs the same starts for the same time.",
        "",
        "**Orbit** is the sense in which the centre of mass circles over many nutation loops: its *slow path*. Each run",
        "is cut into windows of 12 nutations (the nutation period shrinks from 0.2-0.3 s to 0.05 s as a ring decays, so",
        "windows count nutations, not seconds) and in each the slow path is read twice, by filters that share nothing",
        "but the run (verify/circling.py): the CM sampled once per nutation (its winding) and the CM averaged over a",
        "nutation (the area its mean path sweeps). A window's orbit sense counts only where both turn half a turn or",
        "more the same way; otherwise the window is **undecided** and neither measure is preferred. A run **turns",
        "retrograde** when its slow path goes with its spin omega.Z in the first window that decides and against it in",
        "its last window; it is **undecided** when its last window does not decide (end state not read) or fewer than",
        "two windows decide ('too short': fewer than 24 nutations before it falls flat). 'As far as read' is the same",
        "verdict with the last window that decides standing for the end. 'Node-turn reading' is the former criterion --",
        "the net turn of the line of nodes e1, which counts the loops, not the slow path -- on the same windows, for",
        f"comparison only. Output every 2.5 ms: at least {min(ppn) if ppn else '-'} points in the shortest nutation of "
        "any run.",
        "",
        "| mechanism | c | runs | turn retrograde | no turn | undecided (too short) | turn / judged as far as read "
        "| slow path reversed | node-turn reading | rolling direction reversed | fell flat |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]

    def row(m, c, t, roll):
        return (f"| {m} | {c} | {t['runs']} | {t['turned']} | {t['judged'] - t['turned']} "
                f"| {t['undecided']} ({t['too_short']}) | {t['read_turned']}/{t['read_judged']} | {t['orbit_reversal']} "
                f"| {t['node_turn']} | {roll} | {t['fell_flat']} |")

    for m, s in study.items():
        lines += [row(m, pc["c"], pc, pc["roll_reversal"]) for pc in s["per_c"]]
        lines.append(row(f"{m}, control", 0, s["control"], "-"))
    lines += ["", "Windows undecided: " + "; ".join(
        f"{m} {s['windows_undecided']} of {s['windows']} (control {s['control_windows_undecided']} of "
        f"{s['control_windows']})" for m, s in study.items()) + ".", ""]
    lines += ["Slow-path retrograde turns by thickness h and by wall w (turned/judged with the end state read; as far "
              "as read in brackets; over the other axis and both c):", "",
              "| mechanism | " + " | ".join(f"h = {x['h']}" for x in first["by_h"]) + " | "
              + " | ".join(f"w = {x['w']}" for x in first["by_w"]) + " |",
              "|---|" + "---:|" * (len(first["by_h"]) + len(first["by_w"]))]
    for m, s in study.items():
        lines.append(f"| {m} | " + " | ".join(f"{x['turned']}/{x['judged']} ({x['read_turned']}/{x['read_judged']})"
                                               for x in s["by_h"] + s["by_w"]) + " |")
    lines += ["", "**The corners of the maps**, run by run. A sense is *positive* or *negative* about the vertical, "
              "*undecided* where the two measures disagree; *orbit* is the slow path's sense in the first and the last "
              "window that decide (their times), *spin* the sense of $\\omega \\cdot Z$ in the run's first and last "
              "windows, and the *last window* gives its orbit sense and the turns the two measures count there "
              "(once per nutation, averaged). A run too short to cut into windows has nothing to read.", ""]
    for m, s in study.items():
        lines += [f"*{m.replace('-', ' ')}*:", ""]
        lines += [f"- {_body_words(b)}" for b in s["bodies"]]
        lines.append("")
    how = "; ".join(f"{m}: {s['read_turned']} runs turn as far as read ({s['turns_by_orbit_reversal']} of them by "
                    f"the orbit reversing, {s['turns_by_spin_reversal']} by the spin reversing under an orbit that "
                    f"keeps its sense), {s['turned']} with the end state read, against {s['node_turn']} by the "
                    "node-turn reading" for m, s in study.items())
    lines += ["", "**Verdict.** " + " ".join(s["verdict"] + "." for s in study.values()),
              f"How the runs turn -- {how}. Where windows are undecided late in a run the two measures mostly disagree "
              "outright (e.g. -2 turns once per nutation against +9 averaged) or the once-per-nutation samples step "
              "more than a quarter turn (aliased, no reading): near flat the CM circles at 0.6-0.9 turns per nutation, "
              "so the loops and the orbit have no separate time scales and there is no slow path to read. "
              "Conservative controls that turn: "
              + ", ".join(f"{m} {s['control']['turned']} of {s['control']['runs']}" for m, s in study.items()) + ".",
              f"Energy: E + W = E(0) along every run to {max(float(s['max_energy_drift_vs_terms']) for s in study.values()):.0e} "
              "of the energy's scale.", ""]
    for m in study:
        lines += [f"![](figures/retrograde-{m}.png)", "", f"![](figures/retrograde-{m}-roll.png)", ""]
    return lines


_OUTCOME = {"theta_stop": "fell flat", "rim_switch": "rolled onto its other rim"}


def _sense(v) -> str:
    """A sense in words: positive, negative or undecided; None where there is nothing to read."""
    return None if _nan(v) else ("positive" if v > 0 else "negative" if v < 0 else "undecided")


def _pair_words(pair) -> str:
    first, last = (_sense(v) for v in pair)
    if first is None and last is None:
        return "nothing to read"
    return first if first == last else f"{first or 'not read'}, then {last or 'not read'}"


def _body_words(b: dict) -> str:
    """One corner of a map as a sentence (the table's glyphs in words)."""
    head = (f"**{b['body']}** (h = {b['h']}, w = {b['w']}, c = {b['c']}): "
            f"{_OUTCOME.get(b['outcome'], b['outcome'].replace('_', ' '))} at {b['t_stop']} s")
    if b["windows"] is None:
        return head + f", too short to cut into windows: nothing to read; rolling direction {'reversed' if b['roll_reversal'] else 'kept'}."
    parts = [f"{b['windows']} windows, {b['windows_undecided']} undecided"]
    if _sense(b["orbit"][0]) is None and _sense(b["orbit"][1]) is None:
        parts.append("no window decides the orbit")
    else:
        parts.append(f"orbit {_pair_words(b['orbit'])} (windows at {_t(b['t_orbit'][0])} s and {_t(b['t_orbit'][1])} s)")
    parts.append(f"spin {_pair_words(b['spin'])}")
    turns = b["last_window_turns"]
    counted = [f"{v:g} turns {how}" for v, how in zip(turns, ("once per nutation", "averaged")) if v is not None]
    parts.append(f"last window {_sense(b['orbit_last']) or 'not read'}" + (f" ({', '.join(counted)})" if counted else ""))
    read = b["retrograde_by_last_read"] + (f", first retrograde window at {b['t_retrograde']} s"
                                           if b["t_retrograde"] is not None else "")
    parts.append(f"retrograde turn: {b['retrograde_turn']} (as far as read: {read})")
    parts.append(f"node-turn reading {_pair_words(b['node_turn'])}")
    parts.append(f"rolling direction {'reversed' if b['roll_reversal'] else 'kept'}")
    return head + "; " + "; ".join(parts) + "."


def _t(v) -> str:
    return "." if v is None else f"{v:g}"

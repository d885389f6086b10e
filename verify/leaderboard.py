"""The engines' leaderboard: other physics engines run on the reference cases and scored, as data.

``make engines`` (``python -m verify engines``) runs every adapter of ``examples/engines/*_adapter.py``
(Exudyn, MuJoCo, PyBullet, Drake: one module each, see their docstrings for the settings and the
pitfalls) on :data:`CASES` at the engine's defaults and at its best settings, each in a process of
its own (an engine that crashes or hangs costs its own row, named, not the board), beside this suite's
own runs of the same cases in double and quad for scale.  Every run is scored by :func:`verify.score`
against the case's proved and agreeing reference.  The result is ``reports/engines.json`` (one writer:
this module) and ``reports/figures/engines.png`` (digits against wall time); ``make report`` renders
the Engines section from them (:mod:`verify.report.engines`) and never runs an engine itself.

An engine that is not installed gets a row that says so (``pip install -e '.[engines]'``).  Wall times
depend on the machine and its load: compare them within one board.

The two Coulomb cases (``coin-coulomb-slip-1``: rolls, slides from t = 0.0780 to 0.0966, rolls; ``coin-coulomb-skid-1``:
slides from the start, sticks at t = 0.0765) are the coin with finite friction: each adapter sets mu as its engine
combines two surfaces' coefficients (the docstrings say how, and where that rule is written), and its record carries a
``friction`` block, where the run slides by its own contact slip speed (``examples/engines/friction_cases.py``: above
0.1 R/s) beside the reference's switches; :func:`words` says where it sticks.  This suite's own runs of those cases are
the event-driven hybrid (:func:`verify.engine.hybrid.solve`), written in form (b) with the centre of mass's sliding
velocity.  ``python -m verify engines --case NAME`` reruns one case (or a few) and keeps the board's other rows.
"""
from __future__ import annotations

import importlib.util
import json
import math
import subprocess
import sys
import time
from importlib.metadata import version
from pathlib import Path

from models.catalogue import STATE_NAMES

from .expressions import read_value
from .provenance import cpu_model, source_commit, write_atomic
from .scoring import score

ROOT = Path(__file__).resolve().parent.parent
ADAPTERS = ROOT / "examples" / "engines"
#: (case, end time run): the disk and the coin (the ring model as the cylinder engines simulate) over their
#: whole case; the hoop and the paper's ring over their first second (an engine at its best settings takes
#: minutes for 10 s; the score then says "partial")
CASES = (("disk-standard-1", None), ("coin-standard-1", None), ("hoop-general-10", 1.0), ("ring-standard-10", 1.0),
         ("coin-coulomb-slip-1", None), ("coin-coulomb-skid-1", None))
SETTINGS = ("default", "best")
TIMEOUT = 900  # s per engine run: a hung engine is stopped and named
#: digits at which a run is said to agree "to the eye" (a plot), "for engineering" (3) and "as a reference" (10)
WORDS = ((10, "reference quality"), (6, "accurate"), (3, "good to 3 digits"), (1, "right to the eye"),
         (0.3, "qualitatively right"))


def load_adapter(name: str):
    """The adapter module ``examples/engines/<name>_adapter.py`` (examples/engines is not a package)."""
    spec = importlib.util.spec_from_file_location(f"{name}_adapter", ADAPTERS / f"{name}_adapter.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def adapters() -> dict:
    """Engine module name -> path of every adapter present."""
    return {p.stem.removesuffix("_adapter"): p for p in sorted(ADAPTERS.glob("*_adapter.py"))}


_CHILD = """
import importlib.util, json, sys
spec = importlib.util.spec_from_file_location("adapter", {path!r})
adapter = importlib.util.module_from_spec(spec)
try:
    spec.loader.exec_module(adapter)
    record = adapter.run_case({case!r}, {setting!r}, t_end={t_end!r})
except ImportError as err:
    record = {{"outcome": "not installed: " + str(err)}}
except Exception as err:
    record = {{"outcome": "error: " + type(err).__name__ + ": " + " ".join(str(err).split())[:300]}}
print("RECORD " + json.dumps({{k: v for k, v in record.items() if not k.startswith("_")}}, default=str))
"""


def engine_run(name: str, path: Path, case: str, setting: str, t_end) -> dict:
    """One adapter run in a process of its own; its record (or why there is none)."""
    t0 = time.monotonic()
    try:
        proc = subprocess.run([sys.executable, "-c", _CHILD.format(path=str(path), case=case, setting=setting,
                                                                    t_end=t_end)],
                              capture_output=True, text=True, timeout=TIMEOUT, cwd=ROOT)
        lines = [ln for ln in proc.stdout.splitlines() if ln.startswith("RECORD ")]
        record = json.loads(lines[-1][7:]) if lines else {
            "outcome": f"error: exit {proc.returncode}: {' '.join(proc.stderr.split())[-300:]}"}
    except subprocess.TimeoutExpired:
        record = {"outcome": f"error: no result within {TIMEOUT} s"}
    record.setdefault("engine", name)
    record.update({"adapter": name, "case": case, "setting": setting, "t_end_run": t_end,
                   "process_wall_s": round(time.monotonic() - t0, 2)})
    return record


def suite_run(case: str, precision: str, t_end) -> dict:
    """This suite's own run of ``case`` on the case's grid (up to ``t_end``), scored the same way."""
    from .reference.store import DIRECTORY, load_set  # lazy: heyoka; the report imports words() from here
    from .engine.single import solve  # lazy: as load_set

    if _coulomb_case(case) is not None:
        return _suite_hybrid_run(case, precision, t_end)
    (record,) = load_set(DIRECTORY, [case])
    grid = [g for g in record["grid"] if t_end is None or float(g) <= float(t_end) + 1e-12]
    params = {k: read_value(v["exact"]) for k, v in record["model"]["parameters"].items()}
    t0 = time.monotonic()
    sol = solve(record["model"]["name"], grid[-1], record["initial_state"], params, precision=precision,
                t_eval=grid)
    wall = time.monotonic() - t0
    columns = {"t": [float(v) for v in sol.t], **{n: [float(v) for v in sol.y[i]] for i, n in enumerate(STATE_NAMES)}}
    s = score(columns, case)
    return {"engine": "rolling-verify (heyoka)", "version": _suite_version(), "adapter": "suite", "case": case,
            "setting": precision, "parameters": {"tol": "the precision's epsilon", "steps": sol.steps},
            "t_end": float(grid[-1]), "t_end_run": t_end, "wall_s": round(wall, 3), "score": s.to_record(),
            "outcome": sol.outcome}


def _coulomb_case(case: str):
    """The :class:`~verify.reference.cases.ReferenceCase` of a Coulomb case (friction set), else None."""
    from .reference.cases import case as reference_case  # lazy: heyoka; the report imports words() from here

    try:
        c = reference_case(case)
    except ValueError:
        return None
    return c if c.friction is not None else None


def hybrid_form_b(sol, params: dict) -> dict:
    """A hybrid run (:class:`verify.engine.hybrid.HybridSolution`) in form (b), rotation matrix, at its outputs.

    The orientation, omega and C's height and vertical velocity are those of the state (:func:`verify.frames.euler_to_b`,
    which also gives C's rolling velocity v_roll = -omega x r_P); where the body slides its centre of mass moves at
    v_roll + s (cos alpha, sin alpha), s the slip speed and alpha its inertial direction (the contact point's
    velocity u = v_C + omega x r_P is the slip).  A switch time (an output twice, the end of one phase and the
    start of the next, the same state) is kept once.
    """
    import numpy as np  # lazy: the board's text (words, merge_boards) needs no numpy

    from .frames import MATRIX, euler_to_b  # lazy: sympy; the report imports words() from here

    t = np.array([float(v) for v in sol.t])
    keep = np.concatenate([[True], np.diff(t) > 0])
    y = np.array([[float(v) for v in row] for row in sol.y])[:, keep]
    state = {n: y[i] for i, n in enumerate(STATE_NAMES)}
    b = euler_to_b(sol.model.split("+")[0], state, params)
    s = np.array([float(v) for v in sol.slip_speed])[keep]
    alpha = np.nan_to_num(np.array([float(v) for v in sol.slip_direction])[keep])
    columns = {c: np.asarray(b[c], float) for c in MATRIX[1:]}
    columns["t"] = t[keep]
    columns["vx"] = columns["vx"] + s * np.cos(alpha)
    columns["vy"] = columns["vy"] + s * np.sin(alpha)
    return columns


def _suite_hybrid_run(case: str, precision: str, t_end) -> dict:
    """This suite's own run of a Coulomb case (the event-driven hybrid) on the case's grid, scored in form (b)."""
    from .engine.hybrid import solve  # lazy: heyoka; the report imports words() from here
    from models import get_model  # lazy: as solve

    c = _coulomb_case(case)
    grid = [g for g in c.grid() if t_end is None or float(g) <= float(t_end) + 1e-12]
    n = len(grid)
    if [float(g) for g in grid] != [float(grid[-1]) * j / (n - 1) for j in range(n)]:
        raise ValueError(f"case {case}: its grid is not equally spaced from 0 (the hybrid's n_eval needs it)")
    t0 = time.monotonic()
    sol = solve(c.run_model, grid[-1], c.state, c.exact_params, friction=c.friction, velocity=c.velocity,
                precision=precision, n_eval=n)
    wall = time.monotonic() - t0
    params = {q.name: float(c.exact_params.get(q.name, q.default)) for q in get_model(c.model).parameters}
    columns = hybrid_form_b(sol, params)
    on_grid = [float(g) for g in grid]
    at = [j for j, v in enumerate(columns["t"]) if float(v) in on_grid]
    columns = {k: v[at] for k, v in columns.items()}
    record = {"engine": "rolling-verify (heyoka)", "version": _suite_version(), "adapter": "suite", "case": case,
              "setting": precision, "parameters": {"tol": "the precision's epsilon", "steps": sol.steps,
                                                   "model": c.run_model, "mu": c.friction},
              "t_end": float(grid[-1]), "t_end_run": t_end, "wall_s": round(wall, 3), "outcome": sol.outcome,
              "friction": {"mu": c.friction, "velocity": None if c.velocity is None else list(c.velocity),
                           "run": _hybrid_slides(sol), "reference": _hybrid_slides(sol)}}
    try:
        record["score"] = score(columns, case).to_record()
    except Exception as err:  # noqa: BLE001 -- named in the row (a case whose reference file is not made, ...)
        record.update(score=None, outcome=f"error: score: {' '.join(str(err).split())[:300]}")
    return record


def _hybrid_slides(sol) -> dict:
    """Where a hybrid run slides and sticks, from its phases (event-located, exact to the precision)."""
    slides = [[float(f"{float(ph.t_start):.6g}"), None if ph.ended != "sticks" else float(f"{float(ph.t_end):.6g}")]
              for ph in sol.phases if ph.kind == "sliding"]
    first_slip = next((float(ph.t_start) for ph in sol.phases[1:] if ph.kind == "sliding"), None)
    first_stick = next((float(ph.t_end) for ph in sol.phases if ph.kind == "sliding" and ph.ended == "sticks"), None)
    return {"slides": slides, "n_slides": len(slides), "phases": [ph.kind for ph in sol.phases],
            "switch_times": [float(f"{float(x):.6g}") for x in sol.switch_times],
            "slips_at": None if first_slip is None else float(f"{first_slip:.6g}"),
            "sticks_at": None if first_stick is None else float(f"{first_stick:.6g}")}


def _suite_version() -> str:
    from .precision import heyoka_version  # lazy: heyoka; the report imports words() from here

    return f"{version('rolling-verify')}, heyoka {heyoka_version()}"


def words(record: dict) -> str:
    """The run in plain words: fell over, refused, or how many digits it keeps (and, for a Coulomb case, where
    it slides and sticks against the reference)."""
    outcome = str(record.get("outcome", ""))
    s = record.get("score")
    if outcome.startswith("not installed"):
        return "not installed here"
    slides = friction_words(record.get("friction"))
    if outcome.startswith("error") or s is None:
        return "no score: " + outcome + (f"; {slides}" if slides else "")
    if outcome.startswith("fell"):
        return "falls over (wrong)" + (f"; {slides}" if slides else "")
    digits = s["min_digits"]
    said = next((text for bound, text in WORDS if digits >= bound), "no digit right")
    if s.get("energy_rel_error") is not None:  # a Coulomb case: friction takes energy; judge it against the reference's
        if s["energy_rel_error"] > 1e-2:
            said += f"; energy off the reference's by {100 * s['energy_rel_error']:.0f} %"
    elif s.get("energy_rel_drift") is not None and s["energy_rel_drift"] > 1e-2:
        said += f"; energy drifts {100 * s['energy_rel_drift']:.0f} %"
    if slides:
        said += f"; {slides}"
    return said + (" (partial)" if s.get("partial") else "")


def _t(x) -> str:
    return f"{x:.4f}"


def friction_words(friction) -> str:
    """Where a Coulomb run slides and sticks against the reference, in words ('' for a rolling case).

    The run's times are where its contact slip speed crosses the adapters' threshold (0.1 R/s: a stick is seen at
    most 0.4 ms early, a slip from rolling about 1.4 ms late; ``examples/engines/friction_cases.py``), the
    reference's its event-located switches.
    """
    if not friction or not friction.get("run") or not friction.get("reference"):
        return ""
    run, ref = friction["run"], friction["reference"]
    if ref.get("sticks_at") is None and ref.get("slips_at") is None:
        return ""
    ref_slide = (f"{_t(ref['slips_at'])} to {_t(ref['sticks_at'])}" if ref.get("slips_at") is not None
                 else f"0 to {_t(ref['sticks_at'])}")
    if not run.get("n_slides"):
        return f"never slides (the reference slides from {ref_slide})"
    if run.get("sticks_at") is None:
        return f"never sticks (the reference slides from {ref_slide})"
    if ref.get("slips_at") is not None:  # rolls, slides, rolls
        start = "0" if run.get("slips_at") is None else _t(run["slips_at"])
        said = f"slides from {start} to {_t(run['sticks_at'])} (reference {ref_slide})"
    else:  # a skid: slides from the start
        said = f"sticks at t = {_t(run['sticks_at'])} (reference {_t(ref['sticks_at'])})"
    extra = run["n_slides"] - ref.get("n_slides", 1)
    if extra > 0:
        said += f", then slides {extra} more time{'s' if extra > 1 else ''}"
    return said


def run_board(engines=None, cases=CASES, settings=SETTINGS, progress=print) -> dict:
    """Every adapter (or those named) on every case and setting, and the suite's double and quad runs."""
    found = adapters()
    chosen = {k: v for k, v in found.items() if engines is None or k in engines}
    rows = []
    for case, t_end in cases:
        for precision in ("double", "quad"):
            rows.append(suite_run(case, precision, t_end))
            progress(f"suite {precision} {case}: {(rows[-1]['score'] or {}).get('min_digits')} digits")
        for name, path in chosen.items():
            for setting in settings:
                rows.append(engine_run(name, path, case, setting, t_end))
                r = rows[-1]
                progress(f"{name} {setting} {case}: {words(r)} ({r.get('wall_s', '-')} s)")
    for r in rows:
        r["words"] = words(r)
    return {"format": "rolling-verify engines 1", "cases": [case_entry(c, t) for c, t in cases],
            "rows": rows, "machine": cpu_model(), "sources": source_commit()}


def case_entry(case: str, t_end_run) -> dict:
    """The board's entry of a case: its name, the end time run, and for a Coulomb case mu and the skid's velocity."""
    entry = {"case": case, "t_end_run": t_end_run}
    c = _coulomb_case(case)
    if c is not None:
        entry["coulomb"] = {"mu": c.friction, "velocity": None if c.velocity is None else list(c.velocity)}
    return entry


def merge_boards(old: dict, new: dict) -> dict:
    """``old`` with ``new``'s runs in place of its rows for the same (case, adapter, setting); cases in the order
    of :data:`CASES` (then any other), machine and sources from ``new`` (the rerun's), and each row keeps the
    sources it was made at (``sources`` on the rows taken from ``old``)."""
    key = lambda r: (r["case"], r.get("adapter"), r.get("setting"))  # noqa: E731
    fresh = {key(r) for r in new["rows"]}
    kept = [dict(r, sources=r.get("sources") or old.get("sources")) for r in old.get("rows", ()) if key(r) not in fresh]
    entries = {c["case"]: c for c in old.get("cases", ())}
    entries.update({c["case"]: c for c in new["cases"]})
    order = [c for c, _ in CASES if c in entries] + [c for c in entries if c not in dict(CASES)]
    rows = sorted(kept + list(new["rows"]), key=lambda r: order.index(r["case"]) if r["case"] in order else len(order))
    return {**new, "cases": [entries[c] for c in order], "rows": rows}


def figure_png(board: dict) -> bytes:
    """Digits (fewest over the run) against wall time (log), one panel a case, one marker an engine
    (filled: its best settings; open: its defaults, or the suite in double)."""
    import matplotlib  # lazy: matplotlib (0.3 s) only when the figure is drawn

    from . import style  # lazy: as matplotlib

    n = len(board["cases"])
    cols = 2 if n > 1 else 1
    rows = math.ceil(n / cols)
    with matplotlib.rc_context(style.RC):
        fig, axes = style.plt.subplots(rows, cols, figsize=(style.COLUMN_WIDTH, 2.9 * rows + 0.9), sharey=True,
                                       squeeze=False)
        engines = sorted({r["engine"] for r in board["rows"]})
        markers = dict(zip(engines, "osD^vP*X"))
        for ax, c in zip(axes.flat, board["cases"]):
            for r in board["rows"]:
                if r["case"] != c["case"] or not r.get("score") or not r.get("wall_s"):
                    continue
                ax.plot(r["wall_s"], max(r["score"]["min_digits"], 0.0), markers[r["engine"]],
                        mfc="none" if r["setting"] in ("default", "double") else None,
                        label=f"{r['engine'].split(' (')[0]} {r['setting']}")
            ax.set_xscale("log")
            ax.set_xlabel("wall time / s")
            ax.set_ylabel("fewest digits")
            ax.set_title(c["case"] + ("" if c["t_end_run"] is None else f" (first {c['t_end_run']:g} s)"))
        for ax in list(axes.flat)[n:]:
            ax.set_visible(False)
        handles, labels = axes.flat[0].get_legend_handles_labels()
        fig.legend(handles, labels, loc="outside lower center", ncol=5, fontsize=style.MIN_FONT_PT)
        return style.png_bytes(fig)


def rewrite_figure(out="reports") -> Path:
    """``out/figures/engines.png`` again from ``out/engines.json`` (no engine is run)."""
    out = Path(out)
    board = json.loads((out / "engines.json").read_text())
    write_atomic(out / "figures" / "engines.png", figure_png(board))
    return out / "figures" / "engines.png"


def write_board(board: dict, out="reports") -> list:
    """``out/engines.json`` and ``out/figures/engines.png``, each atomically, both rendered before either is written."""
    out = Path(out)
    files = {out / "engines.json": json.dumps(board, indent=1, default=str) + "\n",
             out / "figures" / "engines.png": figure_png(board)}
    for path, data in files.items():
        write_atomic(path, data)
    return list(files)

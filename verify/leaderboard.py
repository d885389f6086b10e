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
"""
from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ADAPTERS = ROOT / "examples" / "engines"
#: (case, end time run): the disk and the coin (the ring model as the cylinder engines simulate) over their
#: whole case; the hoop and the paper's ring over their first second (an engine at its best settings takes
#: minutes for 10 s; the score then says "partial")
CASES = (("disk-standard-1", None), ("coin-standard-1", None), ("hoop-general-10", 1.0), ("ring-standard-10", 1.0))
SETTINGS = ("default", "best")
TIMEOUT = 900  # s per engine run: a hung engine is stopped and named
#: digits at which a run is said to agree "to the eye" (a plot), "for engineering" (3) and "as a reference" (10)
WORDS = ((10, "reference quality"), (6, "accurate"), (3, "good to 3 digits"), (1, "right to the eye"),
         (0.3, "qualitatively right"))


def load_adapter(name: str):
    """The adapter module ``examples/engines/<name>_adapter.py`` (examples/engines is not a package)."""
    import importlib.util

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
    from .reference.store import DIRECTORY, load_set
    from .engine.single import solve
    from .expressions import read_value
    from .scoring import score
    from models.catalogue import STATE_NAMES

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


def _suite_version() -> str:
    from importlib.metadata import version

    import heyoka

    return f"{version('rolling-verify')}, heyoka {heyoka.__version__}"


def words(record: dict) -> str:
    """The run in plain words: fell over, refused, or how many digits it keeps."""
    outcome = str(record.get("outcome", ""))
    s = record.get("score")
    if outcome.startswith("not installed"):
        return "not installed here"
    if outcome.startswith("error") or s is None:
        return "no score: " + outcome
    if outcome.startswith("fell"):
        return "falls over (wrong)"
    digits = s["min_digits"]
    said = next((text for bound, text in WORDS if digits >= bound), "no digit right")
    if s.get("energy_rel_drift") is not None and s["energy_rel_drift"] > 1e-2:
        said += f"; energy drifts {100 * s['energy_rel_drift']:.0f} %"
    return said + (" (partial)" if s.get("partial") else "")


def run_board(engines=None, cases=CASES, settings=SETTINGS, progress=print) -> dict:
    """Every adapter (or those named) on every case and setting, and the suite's double and quad runs."""
    found = adapters()
    chosen = {k: v for k, v in found.items() if engines is None or k in engines}
    rows = []
    for case, t_end in cases:
        for precision in ("double", "quad"):
            rows.append(suite_run(case, precision, t_end))
            progress(f"suite {precision} {case}: {rows[-1]['score']['min_digits']} digits")
        for name, path in chosen.items():
            for setting in settings:
                rows.append(engine_run(name, path, case, setting, t_end))
                r = rows[-1]
                progress(f"{name} {setting} {case}: {words(r)} ({r.get('wall_s', '-')} s)")
    for r in rows:
        r["words"] = words(r)
    from .provenance import cpu_model, source_commit

    return {"format": "rolling-verify engines 1", "cases": [{"case": c, "t_end_run": t} for c, t in cases],
            "rows": rows, "machine": cpu_model(), "sources": source_commit()}


def figure_png(board: dict) -> bytes:
    """Digits (fewest over the run) against wall time (log), one panel a case, one marker an engine
    (filled: its best settings; open: its defaults, or the suite in double)."""
    import math

    import matplotlib

    from . import style

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
    from .provenance import write_atomic

    out = Path(out)
    board = json.loads((out / "engines.json").read_text())
    write_atomic(out / "figures" / "engines.png", figure_png(board))
    return out / "figures" / "engines.png"


def write_board(board: dict, out="reports") -> list:
    """``out/engines.json`` and ``out/figures/engines.png``, each atomically, both rendered before either is written."""
    from .provenance import write_atomic

    out = Path(out)
    files = {out / "engines.json": json.dumps(board, indent=1, default=str) + "\n",
             out / "figures" / "engines.png": figure_png(board)}
    for path, data in files.items():
        write_atomic(path, data)
    return list(files)

"""``animate``: the body rolling in 3D (:mod:`verify.animation`), from a run, a figure's starts or a saved run.

Three ways to say what to draw:

* the run options of ``trajectory`` (``animate disk``, ``animate --start fig5-lhs``, ``animate hoop
  --state theta=pi/2-0.05 --state phidot=30 --t-end 5``);
* ``--figure N [--side lhs|rhs|both]``: the figure's panel starts (:mod:`verify.figure_starts`), side
  by side with one clock (``--figure 5``: the stable and the unstable diameter spin);
* a saved run, ``animate RUN.csv`` (a file of ``trajectory --output``).

The file is ``--out FILE.gif|.mp4|.html`` (default ``<what>.gif`` in the current folder), checked
before anything runs and written atomically.
"""
from __future__ import annotations

from pathlib import Path

from ..guard import Session
from .arguments import UsageError, _positive, _positive_int
from .run_command import RunRequest, add_run_options, output_points, read_request, run

RUN_FILES = (".csv", ".json", ".npz")
#: output points of a run made to be animated, unless --n-eval or the start says otherwise (a frame
#: interpolates between them: the body must not turn far between two points)
N_EVAL_ANIMATION = 20001


def add_parser(sub) -> None:
    a = sub.add_parser("animate", help="the body rolling in 3D: a run, a figure's panels side by side, or a saved run",
                       description="Examples: 'animate disk', 'animate --figure 5 --out fig5.gif' (stable and unstable "
                                   "diameter spin side by side), 'animate run.csv --out run.html'.")
    add_run_options(a)
    a.add_argument("--figure", default=None, metavar="N", help="the paper figure whose panel starts to animate")
    a.add_argument("--side", default=None, help="with --figure: lhs, rhs or both (default: both, side by side)")
    a.add_argument("--n-eval", default=None, help=f"output points of the run (default {N_EVAL_ANIMATION})")
    a.add_argument("--out", default=None, metavar="FILE",
                   help="FILE.gif (Pillow), FILE.mp4 (needs ffmpeg: apt-get install ffmpeg) or FILE.html "
                        "(self-contained, offline); default <model or figure>.gif")
    a.add_argument("--speed", default=None,
                   help="simulated seconds per second of animation (default: the fastest turning shown at one turn "
                        "per second and at most real time, unless the run would then last longer than --max-seconds: "
                        "then sped up to fit, and said so on every frame)")
    a.add_argument("--fps", default="20", help="frames per second (default 20: GIF keeps 1/100 s, so 20, 25, 50 are exact)")
    a.add_argument("--width", default="480", help="width of each panel in pixels (default 480)")
    a.add_argument("--max-seconds", default="12", help="longest animation in seconds (default 12: a GIF of a few MB)")
    a.set_defaults(run=cmd_animate)


def cmd_animate(args, session: Session) -> int:
    from ..animation import FORMATS, AnimationError, animate

    runs_from = _source(args)
    from ..series.files import RunFileError, output_path

    try:
        out = output_path(args.out if args.out else f"{runs_from[1]}.gif", "--out", FORMATS)
    except RunFileError as err:
        raise UsageError(str(err)) from None
    speed = None if args.speed is None else float(_positive(args.speed, "--speed", "0.25 (slow motion) or 2"))
    fps = float(_positive(args.fps, "--fps", "25"))
    width = _positive_int(args.width, "--width", 4000, low=64)
    longest = float(_positive(args.max_seconds, "--max-seconds", "20"))
    runs = runs_from[0](session)
    try:
        record = animate(runs, out, speed=speed, fps=fps, width_px=width * len(runs), max_seconds=longest)
    except AnimationError as err:
        raise UsageError(str(err)) from None
    session.emit(f"wrote {record.file}: {len(runs)} panel(s), {record.frames} frames at {record.fps:g} fps, "
                 f"{record.size[0]} x {record.size[1]} px; {record.speed:g} s of the run per second shown"
                 + (" (sped up from the default rule to fit --max-seconds)" if record.raised else "")
                 + f"\nnext        open {record.file} in a browser or an image viewer")
    return 0


def _source(args):
    """(function session -> [AnimationRun], a name for the default file) from the options."""
    model = args.model
    if args.figure is not None:
        if model is not None or args.start is not None or args.state or args.param:
            raise UsageError("--figure draws the figure's own starts; drop the model, --start, --state and --param")
        return _figure_runs(args), f"fig{_figure_number(args.figure)}"
    if args.side is not None:
        raise UsageError("--side is for --figure N (lhs, rhs or both)")
    if model is not None and Path(model).suffix.lower() in RUN_FILES:
        if args.start is not None or args.state or args.param or args.t_end is not None:
            raise UsageError("a saved run is drawn as it is; drop --start, --state, --param and --t-end")
        return (lambda session: [_file_run(model)]), Path(model).stem
    request = read_request(args)
    return (lambda session: [_live_run(args, session, request, request.model)]), (args.start or model or request.model)


def _figure_number(text) -> int:
    from ..figure_starts import figures_with_runs

    allowed = ", ".join(str(n) for n in figures_with_runs())
    try:
        n = int(str(text).strip())
    except ValueError:
        raise UsageError(f"--figure {text!r} is not a figure number; allowed: {allowed}") from None
    if n not in figures_with_runs():
        raise UsageError(f"--figure {n} has no run to animate; allowed: {allowed}")
    return n


def _figure_runs(args):
    from ..figure_starts import panel_sides, starts_of

    n = _figure_number(args.figure)
    sides = panel_sides(n)
    side = (args.side or "both").strip().lower()
    if side not in ("lhs", "rhs", "both"):
        raise UsageError(f"--side {args.side!r}; allowed: lhs, rhs or both")
    if side != "both" and side not in sides:
        raise UsageError(f"--side {side}: Fig. {n} has {'the sides ' + ', '.join(sides) if sides else 'one panel'}; "
                         f"allowed: {', '.join(sides) or 'both'}")
    wanted = sides if side == "both" else (side,)
    chosen = [s for s in starts_of(n) if s.side is None] if not sides else \
        [next(s for s in starts_of(n, w)) for w in wanted]  # each panel's first start (the caption's own)

    def runs(session):
        out = []
        for start in chosen:
            args.start, args.model = start.name, None
            request = read_request(args)
            out.append(_live_run(args, session, request, f"Fig. {n}{' ' + start.side.upper() if start.side else ''}: "
                                                         f"{start.name}"))
        return out
    return runs


def _live_run(args, session, request: RunRequest, label: str):
    from ..animation import AnimationRun

    n_eval = output_points(args, request, kept=True)
    n_eval = max(n_eval, N_EVAL_ANIMATION) if args.n_eval is None else n_eval
    args.format, args.progress = "text", None
    sol, failure = run(request, args, session, n_eval, f"animate {request.model}")
    params = {k: float(v) for k, v in sol.params.items()}
    label = label if failure is None else f"{label} (stopped: {failure.outcome})"
    return AnimationRun.from_solution(label, request.model, sol, params)


def _file_run(path: str):
    import numpy as np

    from ..animation import AnimationRun
    from ..series.files import RunFileError, read_run

    try:
        columns = read_run(path)
    except RunFileError as err:
        raise UsageError(str(err)) from None
    arrays = {n: columns.as_float(n) for n in ("t", "theta", "phi", "psi", "x", "y")}
    params = {k: float(v) for k, v in columns.meta.get("params", {}).items()}
    return AnimationRun(f"{columns.meta.get('model')}: {Path(path).name}", columns.meta.get("model"), params,
                        **{k: np.asarray(v) for k, v in arrays.items()})

"""``animate``: the body rolling in 3D (:mod:`verify.animation`), from a run, a figure's starts or a saved run.

Three ways to say what to draw:

* the run options of ``trajectory`` (``animate disk``, ``animate --start fig5-lhs``, ``animate hoop
  --state theta=pi/2-0.05 --state phidot=30 --t-end 5``), a body file among them (``animate --body
  rounded-coin``, ``animate --body FILE.toml --state theta=1.2``) and a shipped body with friction
  (``animate --body tippe-top --friction 0.3 --friction-law smooth --slip-scale 10``: the smooth
  law's run and, beside it, the exact Coulomb run from the same start, ``--compare none`` to drop it);
* ``--figure N [--side lhs|rhs|both]``: the figure's panel starts (:mod:`verify.figure_starts`), side
  by side with one clock (``--figure 5``: the stable and the unstable diameter spin);
* a saved run, ``animate RUN.csv`` (a file of ``trajectory --output``).

The file is ``--out FILE.gif|.mp4|.html`` (default ``<what>.gif`` in the current folder), checked
before anything runs and written atomically.

The command line's parser imports this module: numpy, matplotlib, sympy and heyoka are imported inside
the functions that need them (``# lazy:``), so that ``--help`` and the listings load none of them.
"""
from __future__ import annotations

import argparse
from dataclasses import replace
from pathlib import Path

from ..guard import Session
from .arguments import UsageError, _positive, _positive_int
from .run_command import RunRequest, add_run_options, output_points, read_request, run

RUN_FILES = (".csv", ".json", ".npz")
#: output points of a run made to be animated, unless --n-eval or the start says otherwise (a frame
#: interpolates between them: the body must not turn far between two points)
N_EVAL_ANIMATION = 20001
#: The start a shipped body with friction is animated from when neither --state nor --velocity is given: the
#: tippe-top study's (docs/tippe-top.md): the file's [start] (theta = 0.1, psidot = 200 s^-1, above the
#: inversion threshold n_s = 147.4 s^-1) with C at rest, so the contact slips at 20 R/s at t = 0.  Under the
#: smooth law at eps = 10 R/s the top has turned over (theta > 2.5 rad) by 0.91 s and is inverted at 1.17 s;
#: t_end 2 s shows it settled.  A smaller eps inverts later (14.7 s at eps = 0.03): --t-end.
FRICTION_PRESETS = {name: {"velocity": "0,0"} for name in ("tippe-top", "tippe-top-stable", "tippe-top-hanging")}


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
    a.add_argument("--compare", default=None, choices=("coulomb", "none"),
                   help="with --body NAME --friction MU --friction-law smooth: the exact Coulomb run from the same start "
                        "beside the smooth law's (coulomb, the default) or not (none)")
    a.set_defaults(run=cmd_animate)


def cmd_animate(args, session: Session) -> int:
    from ..animation import FORMATS, AnimationError, animate  # lazy: numpy, verify.animation (0.16 s): not --help

    runs_from = source(args)
    from ..series.files import RunFileError, output_path  # lazy: numpy (0.14 s): not --help

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
    lines = [f"wrote {record.file}: {len(runs)} panel(s), {record.frames} frames at {record.fps:g} fps, "
             f"{record.size[0]} x {record.size[1]} px; {record.speed:g} s of the run per second shown"
             + (" (sped up from the default rule to fit --max-seconds)" if record.raised else "")]
    lines += [f"panel       {run.label}" for run in runs] if len(runs) > 1 or args.body is not None else []
    lines += [f"start       {runs_from[2]}"] if runs_from[2] else []
    lines.append(f"next        open {record.file} in a browser or an image viewer"
                 + ("; python -m verify tippe-top for the study's numbers" if args.body is not None
                    and args.friction is not None else ""))
    session.emit("\n".join(lines))
    return 0


def source(args):
    """(function session -> [AnimationRun], a name for the default file, the start in words or None) from the
    parsed options of ``animate`` (:func:`verify.cli.parser.parser`); bad input: :class:`UsageError`.  The
    runs are made when the function is called (the tests read the frames' data through it)."""
    model = args.model
    if args.compare is not None and (args.body is None or args.friction_law != "smooth"):
        raise UsageError(f"--compare {args.compare} is for --body NAME --friction MU --friction-law smooth")
    if args.figure is not None:
        if model is not None or args.start is not None or args.state or args.param or args.body is not None:
            raise UsageError("--figure draws the figure's own starts; drop the model, --body, --start, --state and --param")
        return _figure_runs(args), f"fig{_figure_number(args.figure)}", None
    if args.side is not None:
        raise UsageError("--side is for --figure N (lhs, rhs or both)")
    if model is not None and Path(model).suffix.lower() in RUN_FILES:
        if args.start is not None or args.state or args.param or args.t_end is not None or args.body is not None:
            raise UsageError("a saved run is drawn as it is; drop --body, --start, --state, --param and --t-end")
        return (lambda session: [_file_run(model)]), Path(model).stem, None
    if args.body is not None:
        return _body_source(args)
    request = read_request(args)
    return ((lambda session: [_live_run(args, session, request, request.model)]), (args.start or model or request.model),
            request.start)


def _figure_number(text) -> int:
    from ..figure_starts import figures_with_runs  # lazy: verify.figure_starts (3 ms) only for --figure, not --help

    allowed = ", ".join(str(n) for n in figures_with_runs())
    try:
        n = int(str(text).strip())
    except ValueError:
        raise UsageError(f"--figure {text!r} is not a figure number; allowed: {allowed}") from None
    if n not in figures_with_runs():
        raise UsageError(f"--figure {n} has no run to animate; allowed: {allowed}")
    return n


def _figure_runs(args):
    from ..figure_starts import panel_sides, starts_of  # lazy: as in _figure_number

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


def _body_source(args):
    """(runs, default file name, the start in words) of ``--body FILE|NAME``: rolling, or with --friction one law's run (the smooth
    law's with the exact Coulomb run from the same start beside it, unless --compare none)."""
    from models.bodies import InvalidBody, load  # lazy: sympy (0.5 s) only for --body, not --help

    preset = None
    if args.friction is not None and args.velocity is None and not args.state:
        preset = FRICTION_PRESETS.get(str(args.body))
        if preset is not None:
            args.velocity = preset["velocity"]
    request = read_request(args)  # every check of --body and its friction options (bad input: UsageError)
    try:
        body = load(args.body)
    except InvalidBody as err:  # read_request has read it already; kept for a file changed since
        raise UsageError(str(err)) from None
    if preset is not None:
        request = _with_start(request, f"; C at rest (--velocity {preset['velocity']}, the tippe-top study's start: "
                                       "docs/tippe-top.md)")
    beside = None
    if request.law == "smooth" and (args.compare or "coulomb") == "coulomb":
        twin = argparse.Namespace(**{**vars(args), "friction_law": "coulomb", "slip_scale": None})
        beside = read_request(twin), twin
    name = f"{body.name}-{request.law}" if args.friction is not None else body.name

    def runs(session):
        out = [_live_run(args, session, request, _body_label(body.name, request), body)]
        if beside is not None:
            out.append(_live_run(beside[1], session, beside[0], _body_label(body.name, beside[0]), body))
        return out
    return runs, name, request.start


def _with_start(request: RunRequest, words: str) -> RunRequest:
    return replace(request, start=request.start + words)


def _body_label(name: str, request: RunRequest) -> str:
    """A panel's title: the body, the law, mu and eps (units of the body's length L)."""
    if request.friction is None:
        return f"{name}: rolling without slipping"
    if request.law == "smooth":
        return f"{name}: smooth law, \u03bc = {request.friction}, \u03b5 = {request.slip_scale} L/s"
    return f"{name}: exact Coulomb, \u03bc = {request.friction}"


def _live_run(args, session, request: RunRequest, label: str, body=None):
    from ..animation import AnimationRun  # lazy: numpy, verify.animation (0.16 s): not --help

    n_eval = output_points(args, request, kept=True)
    n_eval = max(n_eval, N_EVAL_ANIMATION) if args.n_eval is None else n_eval
    args.format, args.progress = "text", None
    args._n_eval = n_eval  # the smooth law's run reads its output points here (run_command._run_smooth)
    sol, failure = run(request, args, session, n_eval, f"animate {request.model}")
    params = {k: float(v) for k, v in sol.params.items()}
    label = label if failure is None else f"{label} (stopped: {failure.outcome})"
    return AnimationRun.from_solution(label, request.model, sol, params, body=body, **_slip(sol, request))


def _slip(sol, request: RunRequest) -> dict:
    """The contact's slip (inertial x, y) and phase of a run with friction: the hybrid's phases and (s, alpha),
    or the smooth law's (slip_e1, slip_h) in (e1, h) with its phase by |u| against eps; {} for a rolling run."""
    import numpy as np  # lazy: numpy (0.13 s): not --help
    if hasattr(sol, "phases"):  # exact Coulomb (verify.engine.hybrid): s and alpha where sliding, 0 and NaN rolling
        speed = np.asarray(sol.slip_speed, float)
        alpha = np.nan_to_num(np.asarray(sol.slip_direction, float))
        phase = np.array([sol.phases[i].kind for i in sol.phase_index], dtype=str)
        return {"slip_x": speed * np.cos(alpha), "slip_y": speed * np.sin(alpha), "phase": phase}
    if request.law == "smooth":  # u = slip_e1 e1 + slip_h h, e1 = (cos phi, sin phi), h = Z x e1 (models.smooth_friction)
        phi = np.asarray(sol["phi"], float)
        u1, uh = np.asarray(sol["slip_e1"], float), np.asarray(sol["slip_h"], float)
        eps = float(sol.params["eps"])
        phase = np.where(np.hypot(u1, uh) >= eps, "sliding", "slip < \u03b5")
        return {"slip_x": u1 * np.cos(phi) - uh * np.sin(phi), "slip_y": u1 * np.sin(phi) + uh * np.cos(phi),
                "phase": phase}
    return {}


def _file_run(path: str):
    import numpy as np  # lazy: numpy (0.13 s): not --help

    from ..animation import AnimationRun  # lazy: numpy, verify.animation (0.16 s): not --help
    from ..series.files import RunFileError, read_run  # lazy: numpy (0.14 s): not --help

    try:
        columns = read_run(path)
    except RunFileError as err:
        raise UsageError(str(err)) from None
    arrays = {n: columns.as_float(n) for n in ("t", "theta", "phi", "psi", "x", "y")}
    params = {k: float(v) for k, v in columns.meta.get("params", {}).items()}
    model = columns.meta.get("model")
    extra = {}
    if {"slip_speed", "slip_direction", "phase"} <= set(columns.names):  # a Coulomb run: its slip and phases
        speed, alpha = columns.as_float("slip_speed"), np.nan_to_num(columns.as_float("slip_direction"))
        extra = {"slip_x": speed * np.cos(alpha), "slip_y": speed * np.sin(alpha),
                 "phase": np.asarray(columns.values["phase"], dtype=str)}
    given = (columns.meta.get("given") or {}).get("body")
    if isinstance(model, str) and model.startswith("body:") and given and Path(given).suffix:
        from models.bodies import InvalidBody, load  # lazy: sympy (0.5 s) only for a body file's run, not --help

        try:  # a body file that is not shipped: the file the run was made from
            extra["body"] = load(given)
        except InvalidBody as err:
            raise UsageError(f"run file {path}: {err}") from None
    return AnimationRun(f"{model}: {Path(path).name}", model, params, **{k: np.asarray(v) for k, v in arrays.items()},
                        **extra)

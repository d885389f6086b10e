"""``trajectory``: one run from a model and a start, printed, kept (``--output``) and drawn (``--plot``).

The run's options are shared with ``animate`` (:func:`add_run_options`, :func:`read_request`,
:func:`run`): a model (or an alias such as ``hoop``), a named start (``--start fig5-lhs``, a
reference case, or the model's default when nothing is given), ``--state``/``--param`` values that
may be expressions (``pi/2``), and the end time.  Output files are checked before the run (their
folder must exist) and written atomically after it.
"""
from __future__ import annotations

import argparse
import sys
from dataclasses import dataclass

from models import get_model, sources
from models.catalogue import ALIASES, ALL_NAMES, BODY_PREFIX, COULOMB_NAMES, STATE_NAMES

from ..engine.errors import IntegrationError
from ..guard import Session, isatty
from .arguments import (N_EVAL_MAX, RunFailed, UsageError, _decimal, _positive, _positive_int, _precision, _shown,
                        _value_pairs)
from .output import _dumps, _not_ok, _text, coulomb_record, coulomb_text, trajectory_record

MODEL_CHOICES = ALL_NAMES + COULOMB_NAMES + tuple(ALIASES)
#: output points when the run is kept or drawn and --n-eval is not given (a smooth curve, a frame per point)
N_EVAL_KEPT = 2001
#: the end time of a run from --state alone (no --start, no --t-end), in s
DEFAULT_T_END = "2"


def add_run_options(p: argparse.ArgumentParser) -> None:
    """The options that say which run: model, start, state, parameters, time, precision."""
    p.add_argument("model", nargs="?", default=None,
                   help=f"one of: {', '.join(MODEL_CHOICES)} (optional with --start), or body:NAME for a body file "
                        "(as --body NAME)")
    p.add_argument("--start", default=None, metavar="NAME",
                   help="a named start: a figure's (fig5-lhs) or a reference case's (disk-standard-1); "
                        "'python -m verify starts' lists them.  Without --start and --state: the model's default start")
    p.add_argument("--state", action="append", metavar="NAME=VALUE",
                   help=f"an initial value, overriding the start's (names: {', '.join(STATE_NAMES)}); values may be "
                        "expressions such as pi/2 - 0.05 or sqrt(980/1.25); unset ones are 0 when no --start is given")
    p.add_argument("--param", action="append", metavar="NAME=VALUE", help="a parameter (repeatable; expressions allowed)")
    p.add_argument("--t-end", default=None, help="final time in seconds (default: the start's)")
    p.add_argument("--equations", default="derived", help="derived (default) or paper")
    p.add_argument("--precision", default="double", help="double (default), long, quad or mp:BITS (MPFR, BITS >= 53)")
    p.add_argument("--friction", default=None, metavar="MU",
                   help="a friction coefficient: rolling models stop at the event slips where the motion needs more; "
                        "disk+coulomb and ring+coulomb roll and slide with it")
    p.add_argument("--body", default=None, metavar="FILE",
                   help="a body of revolution from its profile, in place of a model: a TOML body file (any path), a "
                        "shipped body's name (rounded-coin, routh-sphere, prolate-ellipsoid, ...: models/bodies/) or a "
                        "model name body:NAME@HASH printed by an earlier run (docs/bodies.md)")
    p.add_argument("--velocity", default=None, metavar="VX,VY",
                   help="disk+coulomb, ring+coulomb: the centre of mass's horizontal velocity at t = 0 (default: rolling)")
    p.add_argument("--friction-law", default="coulomb", choices=("coulomb", "smooth"),
                   help="with --body (any body file) and --friction: exact Coulomb friction (default; rolls, slides, sticks) or the "
                        "smooth law -mu N u/sqrt(|u|^2 + eps^2) (docs/tippe-top.md)")
    p.add_argument("--slip-scale", default=None, metavar="EPS",
                   help="--friction-law smooth: the slip scale eps of the smooth law, in R/s")


@dataclass(frozen=True)
class RunRequest:
    """What to run, read from the command line (values as text or exact sympy numbers)."""

    model: str
    equations: str
    params: dict
    state: dict
    t_end: str
    friction: object
    velocity: object
    start: str  # how the start was chosen, in words (printed and kept in the files)
    given: dict  # the options as typed (kept in the files' metadata)
    n_eval: int | None = None  # the start's own output grid (a figure's), unless --n-eval is given
    events: bool = True  # False only for a start its source ran without events (Fig. 12)
    body: object = None  # the Model of --body FILE (models.bodies), in place of a model name
    law: str = "coulomb"  # --friction-law, with --body and --friction
    slip_scale: object = None  # --slip-scale, with --friction-law smooth
    body_file: object = None  # the models.bodies.Body of --body (every law), recorded in the run's files


def read_request(args) -> RunRequest:
    """The run the options ask for (bad input: :class:`UsageError`).

    The start's values come first (a named start, or the model's default when neither --start nor
    --state is given), then --param and --state override them one by one.
    """
    from .. import starts  # lazy: verify.starts (12 ms) kept out of --help

    state, params = _value_pairs(args.state, "state"), _value_pairs(args.param, "param")
    if args.model is not None and args.model.startswith(BODY_PREFIX):  # body:NAME[@HASH] in a model's place: --body
        if getattr(args, "body", None) is not None:
            raise UsageError(f"give the body once: the model {args.model} or --body {args.body}")
        args.body, args.model = args.model, None
    if getattr(args, "body", None) is not None:
        return _body_request(args, state, params)
    typed = args.model
    if typed is not None and typed not in MODEL_CHOICES:
        raise UsageError(f"unknown model {typed!r}; allowed: {', '.join(MODEL_CHOICES)}")
    model, fixed = ALIASES.get(typed, (typed, {}))
    for name, value in fixed.items():
        if name in params and not _same_number(params[name], value):
            raise UsageError(f"--param {name}={params[name]}: {typed!r} is the {model} with {name} = {value}; "
                             f"use the model {model!r} for another {name}")
    if args.start is not None:
        try:
            start = starts.find(args.start)
        except KeyError as err:
            raise UsageError(str(err.args[0])) from None
        if model is not None and model.split("+")[0] != start.model:
            raise UsageError(f"--start {args.start} is a start of the model {start.model!r}, not {typed!r}; "
                             f"drop the model or give {start.model!r}")
        how = f"--start {start.name} ({start.source})"
    elif typed is None:
        raise UsageError("give a model (python -m verify models lists them) or --start NAME "
                         "(python -m verify starts lists them)")
    elif not state:
        start = starts.default_start(typed)
        how = f"the default start of {typed}: {start.note}"
    else:
        start = None
        how = "--state as given, unset components 0"
    model = model or start.model
    values = {"params": {}, "state": {}}
    t_end, friction, n_eval, events = None, None, None, True
    if start is not None:
        for group, given in (("params", start.params), ("state", start.state)):
            for name, text in given.items():
                values[group][name] = _start_value(text, f"start {start.name}: {name}")
        t_end, friction, n_eval, events = start.t_end, start.friction, start.n_eval, start.events
    values["params"].update(fixed)
    values["params"].update(params)
    values["state"].update(state)
    if args.t_end is not None:
        t_end = _positive(args.t_end, "--t-end", "2 (seconds)")
        n_eval = None  # a start's own grid belongs to its own end time
    if t_end is None:
        t_end = DEFAULT_T_END
        how += f", t_end {DEFAULT_T_END} s (the default; --t-end to change)"
    if args.friction is not None:
        friction = args.friction
    if model in COULOMB_NAMES and friction is None:
        friction = starts.DEFAULT_FRICTION
        how += f"; Coulomb coefficient mu = {friction} (the default; --friction to change)"
    elif model in COULOMB_NAMES:
        how += f"; Coulomb coefficient mu = {friction}"
    if values["state"]:
        typed_state = {name.strip(): text.strip() for name, _, text in (item.partition("=") for item in args.state or ())}
        shown = {**(start.state if start is not None else {}), **typed_state}
        how += "; initial " + ", ".join(f"{k} = {_short(shown.get(k, v))}" for k, v in values["state"].items()) \
            + " (others 0)"
    given = {"model": typed, "start": args.start, "state": {k: str(v) for k, v in state.items()},
             "params": {k: str(v) for k, v in params.items()}, "t_end": args.t_end, "friction": args.friction}
    return RunRequest(model, args.equations, values["params"], values["state"], str(t_end), friction, args.velocity,
                      how, given, n_eval, events)


def _body_request(args, state: dict, params: dict) -> RunRequest:
    """The run of ``--body FILE``: the body's model, --state (default: tilted to the middle of its domain,
    phidot 1, psidot 10), --param I1/I3/g, --t-end (default 2 s)."""
    from models.bodies import InvalidBody, default_start, load, model_of  # lazy: sympy (0.6 s) kept out of --help

    if args.model is not None or args.start is not None:
        raise UsageError(f"--body {args.body} is the body: drop the model {args.model or ''}{' and ' if args.model and args.start else ''}"
                         f"{'--start ' + args.start if args.start else ''}")
    law = getattr(args, "friction_law", "coulomb")
    if args.friction is None and (args.velocity is not None or law != "coulomb" or getattr(args, "slip_scale", None)):
        raise UsageError("--velocity, --friction-law and --slip-scale take --friction MU with --body")
    if args.friction is None and args.velocity is not None:
        raise UsageError("--body runs roll without slipping unless --friction MU is given")
    if args.equations != "derived":
        raise UsageError(f"--equations {args.equations!r}: a body file has the derived equations only")
    try:
        body = load(args.body)
        model = model_of(body)  # its name: body:NAME (shipped) or body:NAME@HASH (registered: resolves in this process)
    except InvalidBody as err:
        raise UsageError(str(err)) from None
    if not state:
        state, how = default_start(body)
    else:
        how = "--state as given, unset components 0"
    t_end = DEFAULT_T_END if args.t_end is None else str(_positive(args.t_end, "--t-end", "2 (seconds)"))
    if args.t_end is None:
        how += f", t_end {DEFAULT_T_END} s (the default; --t-end to change)"
    given = {"body": str(args.body), "body_model": model.name, "state": {k: str(v) for k, v in state.items()},
             "params": {k: str(v) for k, v in params.items()}, "t_end": args.t_end}
    if args.friction is None:
        return RunRequest(model.name, "derived", params, state, str(t_end), None, None, how, given, body=model,
                          body_file=body)
    return _friction_body_request(args, model, body, params, state, str(t_end), how, given, law)


def _friction_body_request(args, model, body, params, state, t_end, how, given, law) -> RunRequest:
    """``--body FILE --friction MU``: any body file under exact Coulomb friction (the hybrid of
    :mod:`verify.engine.hybrid`, ``body:NAME[@HASH]+coulomb``) or the smooth law (:mod:`verify.engine.smooth`,
    ``body:NAME[@HASH]+smooth``); the engines resolve the registered name and hold the run to their guards (E + W,
    and Jellett's integral for a sphere under the smooth law)."""
    eps = getattr(args, "slip_scale", None)
    if law == "smooth" and eps is None:
        raise UsageError("--friction-law smooth needs --slip-scale EPS (the slip scale, e.g. 1)")
    if law == "coulomb" and eps is not None:
        raise UsageError("--slip-scale is the smooth law's; add --friction-law smooth")
    how += f"; {law} friction mu = {args.friction}" + (f", slip scale eps = {eps}" if eps is not None else "")
    given = {**given, "friction": args.friction, "friction_law": law, "slip_scale": eps, "velocity": args.velocity}
    model_name = f"{model.name}+{law}"
    return RunRequest(model_name, "derived", params, state, t_end, args.friction, args.velocity, how, given,
                      law=law, slip_scale=eps, body_file=body)


def _short(value) -> str:
    """A start value as printed (the run and its files use every digit)."""
    text = str(value)
    if len(text) <= 12:
        return text
    try:
        return f"{float(text):.10g}"
    except ValueError:
        return text


def _start_value(text: str, what: str):
    """A stored start value (a decimal, an exact fraction such as 16720/33489, an expression) read exactly."""
    from ..expressions import read_value  # lazy: verify.expressions (7 ms) kept out of --help

    return read_value(text, what)


def _same_number(a, b) -> bool:
    from ..expressions import read_value  # lazy: verify.expressions (7 ms) kept out of --help

    return read_value(str(a)) == read_value(str(b)) or float(read_value(str(a))) == float(read_value(str(b)))


def run(request: RunRequest, args, session: Session, n_eval: int, label: str):
    """(solution, failure message or None): the run, or the part of it before a named failure.

    A rolling model goes through :func:`verify.engine.single.solve`, a Coulomb body through
    :func:`verify.engine.hybrid.solve`.  Bad input (a state outside the domain, a parameter out of
    range) is a :class:`UsageError`; a run that fails with nothing to show is :class:`RunFailed`.
    """
    from .progress import _Progress  # lazy: .progress (3 ms) kept out of --help

    precision = _precision(args.precision)
    tol = getattr(args, "tol", None)
    if request.law == "smooth":
        return _run_smooth(request, args, precision, tol)
    if request.model in COULOMB_NAMES or request.model.endswith("+coulomb"):
        if request.equations != "derived" or tol is not None or getattr(args, "high_accuracy", False):
            raise UsageError(f"{request.model} takes the derived equations at the precision's epsilon only "
                             "(no --equations paper, --tol, --high-accuracy)")
        friction = _positive(request.friction, "--friction", "0.5 (a Coulomb coefficient > 0)")
        velocity = _velocity(request.velocity)
        from models import coulomb  # lazy: sympy's derivations kept out of --help

        from ..engine import hybrid  # lazy: heyoka, sympy (1 s) kept out of --help

        if isatty(sys.stderr) and not coulomb.sliding_is_kept(request.model):  # a person watches a long wait
            print(f"deriving the sliding equations of {request.model} (sympy, once: minutes for a curved profile; "
                  "kept in the cache for every later run)", file=sys.stderr, flush=True)

        try:
            return hybrid.solve(request.model, request.t_end, request.state, request.params, friction=friction,
                                velocity=velocity, precision=precision, n_eval=n_eval), None
        except ValueError as err:
            raise UsageError(str(err)) from None
        except IntegrationError as err:
            if err.trajectory is None or len(err.trajectory.t) == 0:
                raise RunFailed(f"{err} ({err.outcome})") from None
            return err.trajectory, err
    from ..engine.single import solve  # lazy: heyoka, sympy (1 s) kept out of --help

    if request.velocity is not None:
        raise UsageError(f"--velocity is for the rolling-and-sliding bodies ({', '.join(COULOMB_NAMES)}); "
                         f"{request.model!r} rolls without slipping, its centre's velocity follows from the state")
    if request.body is None and request.equations not in sources(request.model):
        raise UsageError(f"--equations {_shown(request.equations)} for model {request.model!r}; "
                         f"allowed: {', '.join(sources(request.model))}")
    if tol is not None:
        tol = _positive(tol, "--tol", "1e-15 (the Taylor tolerance; default: the precision's epsilon)")
    friction = None if request.friction is None else _positive(request.friction, "--friction",
                                                                "0.5 (a friction coefficient)")
    model = request.body or get_model(request.model, request.equations)
    # by default only where a person watches: text output and stderr a terminal (a log or a test's captured stderr
    # would otherwise gain lines that depend on how long the compilation took: on the machine's load)
    show = args.progress if getattr(args, "progress", None) is not None else (
        getattr(args, "format", "text") == "text" and isatty(sys.stderr))
    bar = _Progress(sys.stderr, label, request.t_end, show)
    with bar:
        try:
            sol = solve(model, request.t_end, request.state, request.params, precision=precision, tol=tol,
                        n_eval=n_eval, high_accuracy=getattr(args, "high_accuracy", False), progress=bar.update,
                        friction=friction, events=request.events)
        except ValueError as err:
            raise UsageError(str(err)) from None
        except IntegrationError as err:  # the run up to its failure, if the integrator kept it
            if err.trajectory is None:
                raise RunFailed(str(err)) from None
            return err.trajectory, err
    return sol, None


def _run_smooth(request: RunRequest, args, precision, tol):
    """The smooth-law run of a shipped body (:func:`verify.engine.smooth.solve`)."""
    from ..engine import smooth  # lazy: heyoka, sympy (0.9 s) kept out of --help

    if request.equations != "derived" or tol is not None or getattr(args, "high_accuracy", False):
        raise UsageError("--friction-law smooth takes the derived equations at the precision's epsilon only "
                         "(no --equations paper, --tol, --high-accuracy)")
    friction = _positive(request.friction, "--friction", "0.3 (a friction coefficient > 0)")
    eps = _positive(request.slip_scale, "--slip-scale", "1 (the slip scale in R/s, > 0)")
    velocity = _velocity(request.velocity)
    body = request.model[len(BODY_PREFIX):-len("+smooth")]  # NAME or NAME@HASH (models.bodies.resolve)
    try:
        return smooth.solve(body, request.t_end, request.state, request.params, friction=friction, slip_scale=eps,
                            velocity=velocity, precision=precision, n_eval=getattr(args, "_n_eval", 101)), None
    except ValueError as err:
        raise UsageError(str(err)) from None
    except IntegrationError as err:
        raise RunFailed(f"{err} ({err.outcome})") from None


def _velocity(text):
    """--velocity VX,VY as two exact decimals, or None; bad input: UsageError naming it."""
    if text is None:
        return None
    parts = text.split(",")
    if len(parts) != 2:
        raise UsageError(f"--velocity {_shown(text)}; allowed: two numbers VX,VY")
    return [_decimal(v, "--velocity VX,VY") for v in parts]


def add_trajectory_parser(sub) -> None:
    t = sub.add_parser("trajectory", help="integrate one model from one start; print, keep (--output) and draw (--plot) it",
                       description="Integrate one model from one start.  Examples: 'trajectory disk' (its default start), "
                                   "'trajectory --start fig5-lhs --output run.csv --plot run.png', "
                                   "'trajectory hoop --state theta=pi/2-0.05 --state phidot=30 --t-end 5'.")
    add_run_options(t)
    t.add_argument("--tol", default=None, help="Taylor tolerance (default: the precision's epsilon)")
    t.add_argument("--n-eval", default=None,
                   help=f"output points from 0 to t_end, 2 to {N_EVAL_MAX} (default 101, or {N_EVAL_KEPT} with --output "
                        "or --plot; a figure's start, at its own t_end, uses the figure's grid)")
    t.add_argument("--high-accuracy", action="store_true",
                   help="heyoka's compensated summation: energy error ~ t^0.5 over 1e6 steps (python -m verify bench)")
    t.add_argument("--output", default=None, metavar="FILE",
                   help="keep the whole run: FILE.csv, FILE.json or FILE.npz (t, the state, invariants, N/(Mg), mu_req, "
                        "with units; every digit: numbers in double and long, decimal strings in quad and MPFR)")
    t.add_argument("--plot", default=None, metavar="FILE",
                   help="draw the run: FILE.png, FILE.svg or FILE.pdf (path, theta, phi, omega3, energy, normal force)")
    t.add_argument("--format", choices=("json", "text"), default="text", help="what is printed: text (default) or JSON")
    t.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress on stderr once a second after the first two (default: on where stderr is a terminal and the format is text)")
    t.set_defaults(run=cmd_trajectory)


def cmd_trajectory(args, session: Session) -> int:
    from ..series.files import RunFileError, output_path  # lazy: numpy (0.25 s) kept out of --help
    from ..series.plot import picture_path  # lazy: numpy (0.25 s) kept out of --help

    request = read_request(args)
    try:  # before the run: nothing is computed for a file that cannot be written
        out = None if args.output is None else output_path(args.output)
        picture = None if args.plot is None else picture_path(args.plot)
    except RunFileError as err:
        raise UsageError(str(err)) from None
    kept = out is not None or picture is not None
    n_eval = output_points(args, request, kept)
    _precision(args.precision)
    args._n_eval = n_eval
    sol, failure = run(request, args, session, n_eval, f"trajectory {request.model}")
    hybrid = hasattr(sol, "phases")
    if request.law == "smooth":
        from .friction_run import smooth_record, smooth_text  # lazy: sympy (0.8 s) kept out of --help

        record = smooth_record(sol)
        record["start"] = request.start
        written = _keep(sol, request, out, picture)
        record["files"] = [str(p) for p in written]
        session.emit(_dumps(record) if args.format == "json" else
                     "\n".join([smooth_text(record), f"start       {request.start}"]
                               + [f"wrote       {p}" for p in written] + [_next_step(args, request, out)]))
        return 0
    if hybrid:
        record = coulomb_record(sol, failure)
    else:
        record = trajectory_record(sol)
        if failure is not None:
            record["outcome"] = failure.outcome
        else:
            reason = _not_ok(sol, request.body or get_model(request.model, request.equations))
            if reason is not None and record["outcome"] == "ok":
                record["outcome"] = "failed:event_detection" if "domain" in reason else "failed:non_finite"
            failure = reason
    record["start"] = request.start
    written = _keep(sol, request, out, picture)
    record["files"] = [str(p) for p in written]
    if args.format == "json":
        session.emit(_dumps(record))
    else:
        text = coulomb_text(record) if hybrid else _text(record)
        lines = [text, f"start       {request.start}"]
        lines += [f"wrote       {p}" for p in written]
        lines.append(_next_step(args, request, out))
        session.emit("\n".join(lines))
    if failure is not None:
        raise RunFailed(str(failure))
    return 0


def output_points(args, request: RunRequest, kept: bool) -> int:
    """--n-eval, else the start's own grid (a figure's), else N_EVAL_KEPT for a run kept or drawn, else 101."""
    if getattr(args, "n_eval", None) is not None:
        return _positive_int(args.n_eval, "--n-eval", N_EVAL_MAX, low=2)
    if request.n_eval is not None:
        return request.n_eval
    return N_EVAL_KEPT if kept else 101


def _keep(sol, request: RunRequest, out, picture) -> list:
    """Write the run's file and picture (each atomically); returns the paths written."""
    if out is None and picture is None:
        return []
    from ..series import run_columns, write_run  # lazy: numpy (0.2 s) kept out of --help
    from ..series.plot import write_plot  # lazy: numpy (0.2 s) kept out of --help
    from .friction_run import body_meta, friction_columns  # lazy: sympy (0.5 s) kept out of --help

    meta = {"start_chosen": request.start, "given": request.given}
    if request.body_file is not None:
        meta["body"] = body_meta(request.body_file, request.given["body"])
    if request.body_file is not None and request.friction is not None and request.body is None:
        columns = friction_columns(sol, meta)  # a body's run with friction: the slip, E + W, C's velocity
    else:
        columns = run_columns(sol, meta)
    written = []
    if out is not None:
        written.append(write_run(columns, out))
    if picture is not None:
        written.append(write_plot(columns, picture))
    return written


def _next_step(args, request: RunRequest, out) -> str:
    """One line pointing to what a person might do next with this run (the options as typed)."""
    if out is not None and "friction_law" in request.given:  # a body with friction: animate takes rolling runs
        return f"next        python -m verify plot {out} --out run.png"
    if out is not None:
        return (f"next        python -m verify plot {out} --out run.png   |   "
                f"python -m verify animate {out} --out run.gif")
    return f"next        python -m verify {' '.join(_typed(args))} --output run.csv --plot run.png"


def _typed(args) -> list:
    """The run's options as they were given (quoted for a shell where needed)."""
    import shlex  # lazy: shlex (2 ms) kept out of --help

    words = ["trajectory"] + ([args.model] if args.model else [])
    for option, value in (("--body", getattr(args, "body", None)), ("--start", args.start), ("--t-end", args.t_end), ("--friction", args.friction),
                          ("--precision", None if args.precision == "double" else args.precision),
                          ("--equations", None if args.equations == "derived" else args.equations),
                          ("--velocity", args.velocity),
                          ("--friction-law", None if getattr(args, "friction_law", "coulomb") == "coulomb" else args.friction_law),
                          ("--slip-scale", getattr(args, "slip_scale", None))):
        if value is not None:
            words += [option, value]
    for option, values in (("--param", args.param), ("--state", args.state)):
        for value in values or ():
            words += [option, value]
    return [shlex.quote(w) for w in words]

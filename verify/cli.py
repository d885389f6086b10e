"""Command line: ``python -m verify {trajectory,models,threshold,spindown,reference,sweep,report,bench} ...``.

Exit statuses: 0 done; 1 a failed integration (or a run the integrator does not mark ``ok`` or
``event:...``), a study that found no root, or an unexpected error; 2 bad input; 130 interrupted
(Ctrl-C); 141 stdout closed under us (``| head``).  Every failure is one line on stderr naming
the bad value and what is allowed; ``--debug`` (anywhere on the line) adds the Python traceback of
an unexpected error.  Under ``--format json`` stdout holds exactly one JSON document (on failure
``{"error": ..., "exit_status": ...}``): whatever heyoka or C++ prints during a computation goes to
stderr (file descriptor 1 is pointed at 2 while the command runs), and the result is written after.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import re
import sys
import threading
import time

from models import ALL_NAMES, get_model, sources
from models.symbols import STATE_NAMES

from .engine.single import IntegrationError, solve
from .guard import Guard, Session, interrupted_line, isatty
from .precision import FIXED, parse_precision

# --- minimum MPFR precision -----------------------------------------------------------------
# verify.precision.MIN_MPFR_BITS (53, double's significand; the argument is there) refuses
# mp:BITS below it in parse_precision; the CLI checks it first so that mp:2, mp:0 and mp:-5
# get the same one line.  The fallback keeps the floor if precision.py does not define it.
try:
    from .precision import MIN_MPFR_BITS as MP_MIN_BITS
except ImportError:  # pragma: no cover
    MP_MIN_BITS = 53
N_EVAL_MAX = 1_000_000
PROGRESS_INTERVAL = 1.0  # seconds between progress lines (twice that before the first)
_DECIMAL = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")
_NON_FINITE = re.compile(r"[+-]?(inf|infinity|nan)", re.IGNORECASE)


class UsageError(Exception):
    """Bad input on the command line (exit status 2)."""


class RunFailed(Exception):
    """The run finished, but not as ok or at a terminal event (exit status 1); the record is printed."""


def _shown(text) -> str:
    text = "" if text is None else str(text)
    return text if text and not any(c.isspace() for c in text) and text.isprintable() else repr(text)


def _decimal(text, what: str) -> str:
    """``text`` if it is a finite decimal number (1.2, -3e-4, .5); else UsageError naming it."""
    s = str(text).strip()
    if _NON_FINITE.fullmatch(s):
        raise UsageError(f"{what}: {s!r} is not a finite number; allowed: a finite decimal number such as 1.2 or -3e-4")
    if not _DECIMAL.fullmatch(s) or not s.isascii():
        raise UsageError(f"{what}: {str(text)!r} is not a number; allowed: a decimal number such as 1.2 or -3e-4")
    return s


def _positive(text, option: str, example: str) -> str:
    """A positive finite decimal for ``option`` (sign and finiteness only: reading it at the run's
    precision, and underflow there, are solve's)."""
    s = str(text).strip()
    bad = UsageError(f"{option} {_shown(text)}: allowed a positive finite number such as {example}")
    if not _DECIMAL.fullmatch(s) or not s.isascii():
        raise bad
    mantissa = s.lstrip("+-").split("e")[0].split("E")[0]
    if s.startswith("-") or not any(c in "123456789" for c in mantissa):
        raise bad
    return s


def _positive_int(text, what: str, top: int | None = None, low: int = 1) -> int:
    s = str(text).strip()
    allowed = f"an integer from {low}{f' to {top}' if top else ' upwards'}"
    if not re.fullmatch(r"[+-]?\d+", s) or not s.isascii():
        raise UsageError(f"{what} {_shown(text)} is not an integer; allowed: {allowed}")
    value = int(s)
    if value < low:
        raise UsageError(f"{what} {s} must be at least {low}; allowed: {allowed}")
    if top is not None and value > top:
        raise UsageError(f"{what} {s} is too large; allowed: {allowed}")
    return value


def _precision(text, option: str = "--precision"):
    """parse_precision, with the MPFR floor (verify.precision.MIN_MPFR_BITS) checked first."""
    import heyoka as hy

    s = str(text).strip()
    allowed = f"double, long, quad or mp:BITS (MPFR, BITS an integer from {MP_MIN_BITS} to {hy.real_prec_max()})"
    m = re.fullmatch(r"mp:\s*([+-]?\d+)", s)
    if m:
        bits = int(m.group(1))
        if not MP_MIN_BITS <= bits <= hy.real_prec_max():
            why = (f"below the MPFR minimum of {MP_MIN_BITS} bits (double's significand)" if bits < MP_MIN_BITS
                   else "above MPFR's largest precision")
            raise UsageError(f"{option} {_shown(text)}: {why}; allowed: {allowed}")
        s = f"mp:{bits}"
    elif s not in FIXED:
        raise UsageError(f"unknown precision {text!r}; allowed: {allowed}")
    try:
        return parse_precision(s)
    except ValueError as err:
        raise UsageError(f"{option} {_shown(text)}: {err}") from None


def _pairs(items, what: str) -> dict:
    out = {}
    for item in items or []:
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise UsageError(f"--{what} {item!r} is not NAME=VALUE")
        if name.strip() in out:
            raise UsageError(f"--{what} {name.strip()} is given twice")
        out[name.strip()] = value.strip()
    return out


def _numeric_pairs(items, what: str) -> dict:
    """NAME=VALUE pairs whose values are decimal numbers (the names are checked by the computation)."""
    pairs = _pairs(items, what)
    for name, value in pairs.items():
        _decimal(value, f"--{what} {name}={_shown(value)}")
    return pairs


# --- trajectory -------------------------------------------------------------------------------

def trajectory_record(sol) -> dict:
    """The JSON object of ``python -m verify trajectory --format json``."""
    p = sol.precision
    return {
        "model": sol.model,
        "equations": sol.equations,
        "precision": p.name,
        "params": {k: p.to_json(v) for k, v in sol.params.items()},
        "t_end": p.to_json(sol.t_end),
        "outcome": sol.outcome,
        "t": p.to_json(sol.t[-1]),
        "steps": sol.steps,
        "state": {n: p.to_json(sol.y[i, -1]) for i, n in enumerate(STATE_NAMES)},
        "invariants": {name: _drifts(p, tr) for name, tr in sol.invariants.items()},
    }


def _drifts(p, tr) -> dict:
    """initial, final and the drifts of one invariant (verify.engine.invariants.InvariantTrace); an
    undefined ratio (NaN: I(0) negligible, or a zero term scale) is null."""
    def ratio(x):
        return None if math.isnan(x) else x

    return {
        "initial": p.to_json(tr.initial),
        "final": p.to_json(tr.final),
        "max_abs_drift": tr.max_abs_drift,
        "max_rel_drift": ratio(tr.max_rel_drift),
        "term_scale": tr.term_scale,
        "max_drift_vs_terms": ratio(tr.max_drift_vs_terms),
        "max_drift_vs_terms_in_eps": ratio(tr.max_drift_vs_terms_in_eps),
    }


def _text(record: dict) -> str:
    lines = [
        f"model       {record['model']} ({record['equations']} equations), precision {record['precision']}",
        "params      " + ", ".join(f"{k}={v}" for k, v in record["params"].items()),
        f"outcome     {record['outcome']} at t = {record['t']} after {record['steps']} steps",
        "state",
    ]
    lines += [f"  {n:<9} {v}" for n, v in record["state"].items()]
    lines.append("invariants  (initial, final; max |I - I(0)|, that / |I(0)|, that / term scale in eps)")
    lines += [f"  {n:<12} {v['initial']}  {v['final']}  {_num(v['max_abs_drift'], '.3e')}  {_num(v['max_rel_drift'], '.3e')}"
              f"  {_num(v['max_drift_vs_terms_in_eps'], '.3g')}"
              for n, v in record["invariants"].items()]
    return "\n".join(lines)


def _num(x, fmt: str) -> str:
    if x is None:
        return "n/a"
    try:
        return format(x, fmt)
    except (TypeError, ValueError):
        return str(x)


def _finite(value) -> bool:
    try:
        return math.isfinite(float(value))
    except (TypeError, ValueError, OverflowError):
        return False


def _not_ok(sol, model) -> str | None:
    """Why a finished run must not be reported as a success, or None.

    The integrator names its own failures (``status < 0``, an outcome other than ``ok`` and
    ``event:<name>``).  On top of that, a run labelled ``ok`` whose final state is not finite or
    whose theta left the model's domain (heyoka's event detection failed and the run went on
    below the plane) is not a success whatever its label.
    """
    outcome = str(sol.outcome)
    if getattr(sol, "status", 0) < 0 or not (outcome == "ok" or outcome.startswith("event:")):
        return f"the integration of {sol.model!r} failed: {getattr(sol, 'message', '') or outcome} (outcome {outcome})"
    if outcome != "ok":
        return None
    final = [sol.y[i, -1] for i in range(len(STATE_NAMES))]
    if not all(_finite(v) for v in final):
        bad = next(n for n, v in zip(STATE_NAMES, final) if not _finite(v))
        return (f"the run of {sol.model!r} reached t = {_num(_float(sol.t[-1]), '.6g')} with a non-finite state "
                f"({bad} = {final[STATE_NAMES.index(bad)]}); the result is not reliable")
    if not model.domain.contains(final[0]):
        return (f"the run of {sol.model!r} ended at theta = {float(final[0]):.6g}, outside its domain "
                f"{float(model.domain.theta_min):.6g} < theta < {float(model.domain.theta_max):.6g}, without its "
                "terminal event (heyoka's event detection failed); the result is not reliable")
    return None


def _float(x) -> float:
    try:
        return float(x)
    except (TypeError, ValueError, OverflowError):
        return math.nan


class _Progress:
    """A progress line on stderr while a single run integrates: time reached, steps, rate.

    ``update(t, steps)`` is what solve's ``progress`` hook calls after each step: it only stores
    the pair.  A daemon thread prints at most once a second (on a terminal, one line rewritten in
    place; otherwise a line per report, less often as the run gets long), starting after the
    first two seconds, so that short runs print nothing.
    """

    def __init__(self, stream, label: str, t_end: str, enabled: bool, interval: float | None = None):
        self.stream, self.label, self.t_end, self.enabled = stream, label, t_end, enabled
        self.interval = PROGRESS_INTERVAL if interval is None else interval
        self.t = self.steps = None
        self.t0 = time.monotonic()
        self.tty = isatty(stream)
        self.shown = False
        self._stop = threading.Event()
        self._thread = None

    def update(self, t, steps) -> None:
        self.t, self.steps = t, steps

    def __enter__(self):
        if self.enabled:
            self._thread = threading.Thread(target=self._loop, name="verify-progress", daemon=True)
            self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
        if self.shown and self.tty:
            self._write("\n")
        return False

    def _loop(self) -> None:
        wait = 2 * self.interval  # runs shorter than that (most, and the JIT) print nothing
        while not self._stop.wait(wait):
            self._write(("\r\x1b[K" if self.tty else "") + self.line() + ("" if self.tty else "\n"))
            self.shown = True
            elapsed = time.monotonic() - self.t0
            wait = self.interval if self.tty or elapsed < 10 * self.interval else 10 * self.interval if elapsed < 600 else 60.0

    def line(self) -> str:
        elapsed = time.monotonic() - self.t0
        t, steps = self.t, self.steps
        if t is None:
            return f"{self.label}: setting up (compiling the equations), t_end = {self.t_end} s, {elapsed:.0f} s elapsed"
        tf, te = _float(t), _float(self.t_end)
        pct = f" ({100 * tf / te:.3g} %)" if te > 0 and math.isfinite(tf) else ""
        rate = steps / elapsed if elapsed > 0 else 0.0
        return (f"{self.label}: t = {tf:.6g} of {self.t_end} s{pct}, {steps:,} steps, {rate:,.0f} steps/s, "
                f"{elapsed:.0f} s elapsed")

    def _write(self, text: str) -> None:
        try:
            self.stream.write(text)
            self.stream.flush()
        except (OSError, ValueError, AttributeError):  # stderr closed (2>&-) or a closed pipe: stop reporting
            self._stop.set()


def cmd_trajectory(args, session: Session) -> int:
    precision = _precision(args.precision)
    if args.model not in ALL_NAMES:
        raise UsageError(f"unknown model {args.model!r}; allowed: {', '.join(ALL_NAMES)}")
    if args.equations not in sources(args.model):
        raise UsageError(f"--equations {_shown(args.equations)} for model {args.model!r}; allowed: {', '.join(sources(args.model))}")
    state, params = _numeric_pairs(args.state, "state"), _numeric_pairs(args.param, "param")
    t_end = _positive(args.t_end, "--t-end", "2 (seconds)")
    tol = None if args.tol is None else _positive(args.tol, "--tol", "1e-15 (the Taylor tolerance; default: the precision's epsilon)")
    n_eval = _positive_int(args.n_eval, "--n-eval", N_EVAL_MAX, low=2)  # at least the start and t_end
    model = get_model(args.model, args.equations)
    show = args.progress if args.progress is not None else args.format == "text"
    bar = _Progress(sys.stderr, f"trajectory {args.model}", t_end, show)
    with bar:
        try:
            sol = solve(model, t_end, state, params, precision=precision, tol=tol, n_eval=n_eval,
                        high_accuracy=args.high_accuracy, progress=bar.update)
        except ValueError as err:
            raise UsageError(str(err)) from None
        except IntegrationError as err:  # the run up to its failure, if the integrator kept it, then exit 1
            if err.trajectory is not None:
                record = trajectory_record(err.trajectory)
                record["outcome"] = err.outcome
                session.emit(_dumps(record) if args.format == "json" else _text(record))
            raise RunFailed(str(err)) from None
    record = trajectory_record(sol)
    failure = _not_ok(sol, model)
    if failure is not None and record["outcome"] in ("ok",):
        # the integrator's own names for these (verify.engine.single.FAILURES)
        record["outcome"] = "failed:event_detection" if "domain" in failure else "failed:non_finite"
    session.emit(_dumps(record) if args.format == "json" else _text(record))
    if failure is not None:
        raise RunFailed(failure)
    return 0


# --- the other commands -------------------------------------------------------------------------

def cmd_models(args, session: Session) -> int:
    records = []
    for name in ALL_NAMES:
        m = get_model(name)
        records.append({
            "model": name,
            "title": m.title,
            "equations": list(sources(name)),
            "parameters": {p.name: {"default": str(p.default), "range": p.allowed(), "description": p.description}
                           for p in m.parameters},
            "domain": f"{m.domain.theta_min} < theta < {m.domain.theta_max}",
            "invariants": list(m.invariant_names()),
            "energy_unit": m.units,
        })
    if args.format == "json":
        session.emit(_dumps(records))
        return 0
    lines = []
    for r in records:
        lines.append(f"{r['model']}: {r['title']} (equations: {', '.join(r['equations'])})")
        for pname, p in r["parameters"].items():
            lines.append(f"    {pname:<3} default {p['default']:<28} range {p['range']:<12} {p['description']}")
        lines.append(f"    domain {r['domain']}; invariants: {', '.join(r['invariants'])}; energy per {r['energy_unit']}")
    session.emit("\n".join(lines))
    return 0


def cmd_threshold(args, session: Session) -> int:
    from .studies.thresholds import bracket, threshold, to_record

    params = _numeric_pairs(args.param, "param")
    nonlinear = None
    try:
        if args.nonlinear_tilt is not None:
            tilt = str(args.nonlinear_tilt).strip()
            if not _DECIMAL.fullmatch(tilt) or not tilt.isascii():
                raise UsageError(f"--nonlinear-tilt {args.nonlinear_tilt!r} is not a number; allowed: (0, 0.1), e.g. 1e-6")
            if not 0 < float(tilt) < 0.1:
                raise UsageError(f"--nonlinear-tilt {tilt} must lie in (0, 0.1); allowed: e.g. 1e-6")
        result = threshold(args.model, args.motion, params)
        if args.nonlinear_tilt is not None:
            nonlinear = (tilt, bracket(args.model, args.motion, tilt, params))
        rec = to_record(result, nonlinear)
    except ValueError as err:
        if str(err).startswith("Could not find root"):
            # mpmath.findroot's ValueError: the study failed for these parameters, the input is
            # well formed (exit 1, as a study that finds no root; thresholds.py raises ValueError
            # for bad input only)
            raise RunFailed(f"threshold {args.model} {args.motion}: the study found no root for these parameters "
                            f"(mpmath: {' '.join(str(err).split())})") from None
        raise UsageError(str(err)) from None
    if args.format == "json":
        session.emit(_dumps(rec))
        return 0
    value = rec["threshold"]["value"]
    lines = [f"{rec['model']} {rec['motion']}: {rec['threshold']['name']} = {value if value else 'none'}"
             f"{'  (' + rec['closed_form'] + ')' if rec['closed_form'] else ''}", f"  {rec['method']}"]
    if args.nonlinear_tilt is not None:
        b = rec.get("bracket")
        if b is None:
            lines.append(f"nonlinear bracket at tilt {tilt}: none (no linear threshold to bracket)")
        else:
            lines.append(f"nonlinear bracket at tilt {b['tilt']}: {rec['threshold']['name']} in [{b['low']}, {b['high']}]")
            lines.append(f"  {b['method']}")
    session.emit("\n".join(lines))
    return 0


def cmd_spindown(args, session: Session) -> int:
    from .studies.spindown import spindown, to_record

    params = _numeric_pairs(args.param, "param")
    theta = _decimal(args.theta, f"--theta {_shown(args.theta)}")
    try:
        rec = to_record(spindown(args.model, theta, args.family, params))
    except ValueError as err:
        raise UsageError(str(err)) from None
    session.emit(_dumps(rec) if args.format == "json" else "\n".join(f"{k:<15} {v}" for k, v in rec.items()))
    return 0


def cmd_reference(args, session: Session) -> int:
    from pathlib import Path

    from . import reference

    directory = Path(args.dir) if args.dir else reference.DIRECTORY
    say = lambda text: print(text, file=sys.stderr, flush=True)  # noqa: E731
    try:
        if args.make:
            if args.precision is not None:
                raise UsageError("--precision is for --check; --make always runs mp:128 and mp:256")
            jobs = _positive_int(args.jobs, "--jobs")
            t0 = time.monotonic()
            session.interrupt_note = f"cases already written to {directory} are kept"
            records = reference.make_set(args.case, jobs=jobs, directory=directory, progress=say)
            say(f"wrote {len(records)} case(s) to {directory} in {time.monotonic() - t0:.0f} s")
            return 0
        checks = reference.check_set(args.precision or "double", args.case, directory, progress=say)
    except ValueError as err:
        raise UsageError(str(err)) from None
    session.emit(_dumps([c.to_record() for c in checks]) if args.format == "json" else reference.render_checks(checks))
    failed = [c.case for c in checks if not c.ok]
    if failed:
        raise RunFailed(f"{len(failed)} case(s) out of bound: {', '.join(failed)}")
    return 0


def cmd_sweep(args, session: Session) -> int:
    from pathlib import Path

    from . import sweep
    from .provenance import write_atomic

    try:
        spec = sweep.load(args.spec, store=args.store)
        threads = _positive_int(args.threads, "--threads") if args.threads is not None else None
        if args.plot:
            if args.dask is not None:
                raise UsageError("--plot draws from the store; it does not run anything (drop --dask)")
            if not Path(spec.store).exists():
                raise UsageError(f"no store {spec.store} yet: run 'python -m verify sweep {args.spec}' first")
            from .sweep.plot import render

            with sweep.Store(spec) as store:
                rows = store.rows()
            if not rows:
                raise UsageError(f"the store {spec.store} holds no rows yet")
            out = Path(args.out) if args.out else Path(spec.store).with_suffix(".png")
            if out.is_dir():
                raise UsageError(f"--out {args.out} is a folder; allowed: a file name for the PNG, such as "
                                 f"{out / Path(spec.store).with_suffix('.png').name}")
            _output_folder(str(out.parent))
            write_atomic(out, render(spec, rows))
            session.emit(f"wrote {out} ({len(rows)} of {spec.n_points} trajectories)")
            return 0
        session.interrupt_note = (f"the store {args.store or spec.store} keeps the finished chunks; "
                                  "rerun the same command to resume")
        result = sweep.run_sweep(spec, dask=args.dask, threads=threads, progress=not args.quiet, yes=args.yes)
    except (sweep.SpecError, sweep.StoreError, sweep.ClusterError) as err:
        raise UsageError(str(err)) from None
    session.emit(f"{spec.name}: {result.rows} of {spec.n_points} trajectories in {result.store} "
                 f"({result.chunks_run} chunks run, {result.chunks_skipped} already there; {result.where}; "
                 f"{result.seconds:.1f} s)")
    return 0


def _output_folder(folder: str) -> str:
    from .provenance import writable_folder

    try:
        writable_folder(folder)
    except ValueError as err:
        raise UsageError(f"--out: {err}") from None
    return folder


def cmd_report(args, session: Session) -> int:
    from .report import write_report

    write_report(_output_folder(args.out), bench=not args.no_bench)
    return 0


def cmd_bench(args, session: Session) -> int:
    from .bench import run_benchmarks, write_benchmarks

    try:
        import scipy  # noqa: F401
    except ImportError:
        raise UsageError("the benchmark compares with scipy: pip install scipy (or the project's [bench] extra)") from None
    out = _output_folder(args.out)
    t0 = time.monotonic()
    write_benchmarks(run_benchmarks(quick=args.quick, progress=lambda s: print(s, file=sys.stderr, flush=True)), out)
    session.emit(f"wrote {out}/BENCHMARKS.md, benchmarks.json and figures/bench-*.png ({time.monotonic() - t0:.0f} s)")
    return 0


# --- JSON -------------------------------------------------------------------------------------

def _json_safe(obj):
    """NaN and infinities (which JSON has no numbers for) as null, recursively."""
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, dict):
        return {k: _json_safe(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_json_safe(v) for v in obj]
    return obj


def _dumps(obj) -> str:
    return json.dumps(_json_safe(obj), indent=2, allow_nan=False)


# --- the parser -------------------------------------------------------------------------------

class _Parser(argparse.ArgumentParser):
    """argparse, with its errors as one line (UsageError) instead of a usage block and exit."""

    def error(self, message):
        raise UsageError(f"{message} (see '{self.prog} --help')")


def parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="python -m verify", description=__doc__.splitlines()[0])
    ap.add_argument("--debug", action="store_true",
                    help="show the Python traceback of an unexpected error (may be given anywhere on the line)")
    sub = ap.add_subparsers(dest="command", required=True)

    t = sub.add_parser("trajectory", help="integrate one model from one state")
    t.add_argument("model", help=f"one of: {', '.join(ALL_NAMES)}")
    t.add_argument("--equations", default="derived", help="derived (default) or paper")
    t.add_argument("--param", action="append", metavar="NAME=VALUE", help="a parameter (repeatable)")
    t.add_argument("--state", action="append", metavar="NAME=VALUE",
                   help=f"an initial value, unset ones are 0 (names: {', '.join(STATE_NAMES)})")
    t.add_argument("--t-end", required=True, help="final time in seconds")
    t.add_argument("--precision", default="double",
                   help=f"double (default), long, quad or mp:BITS (MPFR, BITS >= {MP_MIN_BITS})")
    t.add_argument("--tol", default=None, help="Taylor tolerance (default: the precision's epsilon)")
    t.add_argument("--n-eval", default="101", help=f"output points from 0 to t_end (default 101; 2 to {N_EVAL_MAX})")
    t.add_argument("--high-accuracy", action="store_true",
                   help="heyoka's compensated summation: energy error ~ t^0.5 over 1e6 steps (python -m verify bench)")
    t.add_argument("--format", choices=("json", "text"), default="text")
    t.add_argument("--progress", action=argparse.BooleanOptionalAction, default=None,
                   help="progress on stderr once a second after the first two (default: on with --format text, off with json)")
    t.set_defaults(run=cmd_trajectory)

    m = sub.add_parser("models", help="list the models, their parameters and invariants")
    m.add_argument("--format", choices=("json", "text"), default="text")
    m.set_defaults(run=cmd_models)

    th = sub.add_parser("threshold", help="linear stability threshold of a steady motion")
    th.add_argument("model")
    th.add_argument("motion", help="diameter-spin, straight-line, precession or sleeping (as the model has them)")
    th.add_argument("--param", action="append", metavar="NAME=VALUE")
    th.add_argument("--nonlinear-tilt", default=None, metavar="TILT",
                    help="also bracket the threshold by bisection on the full equations with this tilt (e.g. 1e-6)")
    th.add_argument("--format", choices=("json", "text"), default="text")
    th.set_defaults(run=cmd_threshold)

    sd = sub.add_parser("spindown", help="exact steady spin-down state at a tilt, against Eq. 45 / Eq. 61")
    sd.add_argument("model", help="disk or ring")
    sd.add_argument("--theta", required=True)
    sd.add_argument("--family", default="cm-at-rest", help="cm-at-rest (default) or zero-vertical-spin")
    sd.add_argument("--param", action="append", metavar="NAME=VALUE")
    sd.add_argument("--format", choices=("json", "text"), default="text")
    sd.set_defaults(run=cmd_spindown)

    ref = sub.add_parser("reference", help="make or check the reference trajectories (reports/reference/)")
    job = ref.add_mutually_exclusive_group(required=True)
    job.add_argument("--make", action="store_true", help="compute the set at mp:128 and mp:256 (tens of minutes)")
    job.add_argument("--check", action="store_true", help="re-integrate every case and compare with the certified digits")
    ref.add_argument("--precision", default=None, help="for --check: double (default), long or quad")
    ref.add_argument("--case", action="append", metavar="NAME", help="only this case (repeatable)")
    ref.add_argument("--jobs", default="2", help="for --make: processes (default 2)")
    ref.add_argument("--dir", default=None, help="the set's folder (default: reports/reference)")
    ref.add_argument("--format", choices=("json", "text"), default="text")
    ref.set_defaults(run=cmd_reference)

    sw = sub.add_parser("sweep", help="run (or resume) a parameter sweep described by a TOML file")
    sw.add_argument("spec", help="the sweep's TOML file (e.g. verify/sweep/specs/disk-diameter-spin.toml)")
    sw.add_argument("--dask", default=None, metavar="ADDRESS",
                    help="run the chunks on a Dask cluster (tcp://host:port, or 'local' for one on this machine)")
    sw.add_argument("--plot", action="store_true", help="draw the map(s) from the store instead of running")
    sw.add_argument("--store", default=None, help="the store file (default: the spec's)")
    sw.add_argument("--out", default=None, help="with --plot: the PNG (default: the store's name with .png)")
    sw.add_argument("--threads", default=None, help="threads on this machine (default: every core)")
    sw.add_argument("--quiet", action="store_true", help="no progress bar")
    sw.add_argument("--yes", action="store_true",
                    help="run a sweep beyond the size limits (points, memory, disk, time) that it otherwise refuses")
    sw.set_defaults(run=cmd_sweep)

    r = sub.add_parser("report", help="run the verification and write reports/")
    r.add_argument("--out", default="reports", help="output folder (default: reports)")
    r.add_argument("--no-bench", action="store_true", help="skip the benchmarks (BENCHMARKS.md is left as it is)")
    r.set_defaults(run=cmd_report)

    b = sub.add_parser("bench", help="benchmarks: solve, sweeps and maps against bare heyoka, energy error, work against "
                                     "precision, JIT cost")
    b.add_argument("--out", default="reports", help="output folder (default: reports)")
    b.add_argument("--quick", action="store_true", help="small sizes (for trying the command; not for the report)")
    b.set_defaults(run=cmd_bench)
    return ap


def _options(ap: argparse.ArgumentParser):
    """(every option string, those that take a value) over the parser and its subparsers."""
    known, valued = set(), set()
    stack = [ap]
    while stack:
        p = stack.pop()
        for action in p._actions:  # argparse keeps no public list of a parser's actions
            if isinstance(action, argparse._SubParsersAction):
                stack.extend(action.choices.values())
                continue
            known.update(action.option_strings)
            if action.option_strings and action.nargs is None:
                valued.update(action.option_strings)
    return known, valued


def _prepare(argv: list, ap: argparse.ArgumentParser) -> tuple:
    """(argv without --debug, debug): ``--opt VALUE`` becomes ``--opt=VALUE`` where VALUE starts
    with '-' and is not itself an option (``--tol -1e-15``: argparse would take -1e-15 for an
    option and report "expected one argument"); ``--debug`` is taken out wherever it stands."""
    known, valued = _options(ap)

    def is_option(tok: str) -> bool:
        head = tok.split("=", 1)[0]
        return head in known or (head.startswith("--") and len(head) > 2 and any(k.startswith(head) for k in known))

    out, debug, i = [], False, 0
    while i < len(argv):
        tok = argv[i]
        if tok == "--":
            out.extend(argv[i:])
            break
        if tok == "--debug":
            debug = True
        elif (tok in valued and i + 1 < len(argv) and argv[i + 1].startswith("-") and argv[i + 1] not in ("-", "--")
              and not is_option(argv[i + 1])):
            out.append(f"{tok}={argv[i + 1]}")
            i += 1
        else:
            out.append(tok)
        i += 1
    return out, debug


def _wants_json(argv: list) -> bool:
    for i, tok in enumerate(argv):
        if tok == "--format=json" or (tok == "--format" and i + 1 < len(argv) and argv[i + 1] == "json"):
            return True
    return False


# --- main -------------------------------------------------------------------------------------

def _say(stream, line: str) -> None:
    if stream is None:  # stderr closed (2>&-): print(file=None) would write to stdout
        return
    try:
        print(line, file=stream, flush=True)
    except (OSError, ValueError, AttributeError):  # stderr closed: nothing more we can do
        pass


def main(argv=None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    out, err = sys.stdout, sys.stderr
    session = Session(_wants_json(argv))
    debug = "--debug" in argv

    def fail(code: int, line: str) -> int:
        line = " ".join(line.split())  # one line, whatever the message (mpmath's have two)
        if session.json_mode and not session.out:
            session.emit(json.dumps({"error": line, "exit_status": code}))
        _say(err, f"error: {line}")
        return code

    code = 0
    try:
        try:
            ap = parser()
            argv, debug = _prepare(argv, ap)
            try:
                args = ap.parse_args(argv)
            except SystemExit as exc:  # --help
                code = exc.code if isinstance(exc.code, int) else 0
                return code
            with Guard(session, err):
                code = args.run(args, session)
        except UsageError as exc:
            code = fail(2, str(exc))
        except RunFailed as exc:
            code = fail(1, str(exc))
        except (IntegrationError, RuntimeError) as exc:  # a failed run or a study that found no root
            if debug:
                import traceback

                traceback.print_exc(file=err)
            code = fail(1, str(exc) or type(exc).__name__)
        except KeyboardInterrupt:
            if debug:
                import traceback

                traceback.print_exc(file=err)
            code = fail(130, interrupted_line(session))
        except BrokenPipeError:
            raise
        except Exception as exc:  # noqa: BLE001 - the CLI shows no traceback unless asked
            if debug:
                import traceback

                traceback.print_exc(file=err)
                code = fail(1, f"unexpected {type(exc).__name__}: {_one_line(exc)}")
            else:
                code = fail(1, f"unexpected {type(exc).__name__}: {_one_line(exc)} "
                               "(a bug; rerun with --debug for the traceback)")
        if session.out and out is None:  # stdout closed (>&-)
            _say(err, "error: stdout is closed; the result was not written")
            return code or 1
        for text in session.out:
            out.write(text + "\n")
        if out is not None:
            out.flush()
        return code
    except BrokenPipeError:
        # The reader went away (| head): stop quietly.  Point stdout at devnull so that the
        # interpreter's final flush does not fail again, and exit as a process killed by SIGPIPE.
        try:
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, out.fileno())
            os.close(devnull)
        except (OSError, ValueError, AttributeError):
            pass
        return 141
    except KeyboardInterrupt:  # while writing the result
        _say(err, f"error: {interrupted_line(session)}")
        return 130


def _one_line(exc: BaseException) -> str:
    text = " ".join(str(exc).split())
    return text[:300] + ("..." if len(text) > 300 else "") if text else "(no message)"

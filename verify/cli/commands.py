"""The commands: ``trajectory``, ``models``, ``threshold``, ``spindown``, ``reference``, ``score``, ``sweep``, ``report``, ``bench``; each
reads its arguments, runs, and hands its output to the session."""
from __future__ import annotations

import math
import sys
import time

from models import ALL_NAMES, COULOMB_NAMES, get_model, sources
from models.symbols import STATE_NAMES

from ..engine.single import IntegrationError, solve
from ..guard import Session
from .arguments import (_DECIMAL, N_EVAL_MAX, RunFailed, UsageError, _decimal, _numeric_pairs, _positive,
                        _positive_int, _precision, _shown)
from .output import _dumps, _not_ok, _text, trajectory_record
from .progress import _Progress


def cmd_trajectory(args, session: Session) -> int:
    precision = _precision(args.precision)
    if args.model in COULOMB_NAMES:
        return _coulomb_trajectory(args, session, precision)
    if args.model not in ALL_NAMES:
        raise UsageError(f"unknown model {args.model!r}; allowed: {', '.join(ALL_NAMES)}")
    if args.equations not in sources(args.model):
        raise UsageError(f"--equations {_shown(args.equations)} for model {args.model!r}; allowed: {', '.join(sources(args.model))}")
    state, params = _numeric_pairs(args.state, "state"), _numeric_pairs(args.param, "param")
    t_end = _positive(args.t_end, "--t-end", "2 (seconds)")
    tol = None if args.tol is None else _positive(args.tol, "--tol", "1e-15 (the Taylor tolerance; default: the precision's epsilon)")
    n_eval = _positive_int(args.n_eval, "--n-eval", N_EVAL_MAX, low=2)  # at least the start and t_end
    friction = None if args.friction is None else _positive(args.friction, "--friction", "0.5 (a friction coefficient)")
    if getattr(args, "velocity", None) is not None:
        raise UsageError(f"--velocity is for the rolling-and-sliding bodies ({', '.join(COULOMB_NAMES)}); "
                         f"{args.model!r} rolls without slipping, its centre's velocity follows from the state")
    model = get_model(args.model, args.equations)
    show = args.progress if args.progress is not None else args.format == "text"
    bar = _Progress(sys.stderr, f"trajectory {args.model}", t_end, show)
    with bar:
        try:
            sol = solve(model, t_end, state, params, precision=precision, tol=tol, n_eval=n_eval,
                        high_accuracy=args.high_accuracy, progress=bar.update, friction=friction)
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


def _coulomb_trajectory(args, session: Session, precision) -> int:
    """``trajectory disk+coulomb|ring+coulomb --friction MU [--velocity VX,VY]``: phases, switches, E + W."""
    from ..engine import hybrid

    if args.friction is None:
        raise UsageError(f"{args.model} needs --friction MU (the Coulomb coefficient, >= 0)")
    if args.equations != "derived" or args.tol is not None or args.high_accuracy:
        raise UsageError(f"{args.model} takes the derived equations at the precision's epsilon only "
                         "(no --equations paper, --tol, --high-accuracy)")
    state, params = _numeric_pairs(args.state, "state"), _numeric_pairs(args.param, "param")
    t_end = _positive(args.t_end, "--t-end", "2 (seconds)")
    n_eval = _positive_int(args.n_eval, "--n-eval", N_EVAL_MAX, low=2)
    friction = _decimal(args.friction, "--friction", "0.5 (a Coulomb coefficient >= 0)")
    if friction.startswith("-") and any(c in "123456789" for c in friction):
        raise UsageError(f"--friction {friction!r}: allowed a Coulomb coefficient >= 0 such as 0.5")
    velocity = None
    if args.velocity is not None:
        velocity = args.velocity.split(",")
        if len(velocity) != 2:
            raise UsageError(f"--velocity {_shown(args.velocity)}; allowed: two numbers VX,VY")
        velocity = [_decimal(v, "--velocity VX,VY") for v in velocity]
    try:
        sol = hybrid.solve(args.model, t_end, state, params, friction=friction, velocity=velocity,
                           precision=precision, n_eval=n_eval)
        failed = None
    except ValueError as err:
        raise UsageError(str(err)) from None
    except IntegrationError as err:
        if err.trajectory is None or len(err.trajectory.t) == 0:
            raise RunFailed(f"{err} ({err.outcome})") from None
        sol, failed = err.trajectory, err
    p = sol.precision
    record = {
        "model": sol.model, "precision": p.name, "params": {k: p.to_json(v) for k, v in sol.params.items()},
        "outcome": failed.outcome if failed is not None else sol.outcome, "message": str(failed or sol.message),
        "phases": [{"kind": ph.kind, "t_start": p.to_json(ph.t_start), "t_end": p.to_json(ph.t_end), "ended": ph.ended}
                   for ph in sol.phases if ph.t_end is not None],
        "switch_times": [p.to_json(t) for t in sol.switch_times if t is not None],
        "t": p.to_json(sol.t[-1]), "state": {n: p.to_json(sol.y[i, -1]) for i, n in enumerate(STATE_NAMES)},
        "energy_plus_work_drift_in_eps": sol.energy_plus_work_drift_in_eps,
    }
    if args.format == "json":
        session.emit(_dumps(record))
    else:
        lines = [f"{record['model']} ({record['precision']}), mu = {record['params']['mu']}: {record['outcome']}"]
        lines += [f"  {ph['kind']:<8} {ph['t_start']} -> {ph['t_end']}  ({ph['ended']})" for ph in record["phases"]]
        lines += [f"  {n:<9} {v}" for n, v in record["state"].items()]
        lines.append(f"  E + W drift: {record['energy_plus_work_drift_in_eps']:.3g} eps of E's term scale")
        if failed is not None:
            lines.append(f"  {record['message']}")
        session.emit("\n".join(lines))
    if failed is not None:
        raise RunFailed(str(failed))
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
    from ..studies.thresholds import bracket, threshold, to_record

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
    from ..studies.spindown import spindown, to_record

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

    from .. import reference

    directory = Path(args.dir) if args.dir else reference.DIRECTORY
    say = lambda text: print(text, file=sys.stderr, flush=True)  # noqa: E731
    if args.export is None and args.format == "csv":
        raise UsageError("--format csv is for --export; --check prints text or json")
    mode = "--export" if args.export is not None else "--prove" if args.prove else "--make" if args.make else "--check"
    for option, value, modes in (("--until", args.until, ("--prove",)), ("--budget", args.budget, ("--prove",)),
                                 ("--jobs", args.jobs, ("--make",)), ("--format", args.format, ("--check", "--export"))):
        if value is not None and mode not in modes:
            raise UsageError(f"{option} is for {' and '.join(modes)}, not {mode}")
    try:
        if args.export is not None:
            if not args.export.strip():
                raise UsageError("--export '': allowed a folder name (a new or empty folder, or an earlier export)")
            if args.format not in ("csv", "json"):
                raise UsageError(f"--export needs --format csv or json (got {args.format or 'none'})")
            if args.precision is not None or args.case:
                raise UsageError("--export writes every case; --precision and --case are for --check and --make")
            from ..reference.export import export_set

            written = export_set(Path(args.export), args.format, directory)
            if args.format == "json":
                session.emit(_dumps({"written": [str(p) for p in written]}))
            say(f"wrote {len(written)} file(s) to {args.export}")
            return 0
        if args.prove:
            return _prove(args, directory, say)
        if args.make:
            if args.precision is not None:
                raise UsageError("--precision is for --check; --make always runs mp:128 and mp:256")
            jobs = _positive_int(args.jobs or "2", "--jobs")
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


def _prove(args, directory, say) -> int:
    """``reference --prove``: each case of <= 10 s (or those named) enclosed, resuming stored proofs."""
    from fractions import Fraction

    from ..reference import load_set
    from ..reference.proved import prove_case, settings_of, write_summary

    precision = args.precision or "mp:128"
    bits = precision[3:] if precision.startswith("mp:") else ""
    if not bits.isdigit() or not 64 <= int(bits) <= 4096:
        raise UsageError(f"--precision {precision!r}: --prove needs mp:BITS with 64 <= BITS <= 4096 (e.g. mp:128)")
    budget = math.inf if args.budget is None else _positive(args.budget, "--budget", "600")
    until = None
    if args.until is not None:
        try:
            until = Fraction(args.until)
        except (ValueError, ZeroDivisionError):
            raise UsageError(f"--until {args.until!r} is not a number; give a grid time such as 1 or 0.25") from None
        if until <= 0:
            raise UsageError(f"--until {args.until!r}: must be a positive time")
    records = [r for r in load_set(directory, args.case) if args.case or Fraction(r["t_end"]) <= 10]
    for record in records:
        proof = prove_case(record, directory=directory, budget=float(budget), until=until,
                           settings=settings_of(int(bits)), progress=say)
        say(f"{record['name']}: proved to t = {proof['times'][-1]} of {record['t_end']}"
            + (f" ({proof['stopped']})" if proof["stopped"] else ""))
        write_summary(directory)
    return 0


def cmd_score(args, session: Session) -> int:
    from pathlib import Path

    from ..reference import DIRECTORY
    from ..scoring import START_TOLERANCE, score

    tol = START_TOLERANCE if args.start_tol is None else float(_positive(args.start_tol, "--start-tol", "1e-6"))
    if not tol < 1:  # a tolerance of a whole scale or more (or one that overflows to inf) checks no start at all
        raise UsageError(f"--start-tol {args.start_tol}: allowed a fraction of each component's scale below 1, "
                         "such as 1e-6")
    try:
        result = score(args.run_file, args.case, directory=Path(args.dir) if args.dir else DIRECTORY, start_tolerance=tol)
    except ValueError as err:  # InvalidRun and an unknown case: bad input
        raise UsageError(str(err)) from None
    session.emit(_dumps(result.to_record()) if args.format == "json" else result.table())
    return 0


def cmd_sweep(args, session: Session) -> int:
    from pathlib import Path

    from .. import sweep
    from ..provenance import write_atomic

    try:
        spec = sweep.load(args.spec, store=args.store)
        threads = _positive_int(args.threads, "--threads") if args.threads is not None else None
        if args.plot:
            if args.dask is not None:
                raise UsageError("--plot draws from the store; it does not run anything (drop --dask)")
            if not Path(spec.store).exists():
                raise UsageError(f"no store {spec.store} yet: run 'python -m verify sweep {args.spec}' first")
            from ..sweep.plot import render

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
    from ..provenance import writable_folder

    try:
        writable_folder(folder)
    except ValueError as err:
        raise UsageError(f"--out: {err}") from None
    return folder


def cmd_report(args, session: Session) -> int:
    from ..report.write import MissingResults, ReportIncomplete, read_results, write_report

    if args.fresh and args.render_only:
        raise UsageError("--fresh recomputes every job and --render-only computes none; give one of them")
    try:
        if args.render_only:
            read_results(args.out)  # before anything is created: nothing to render from is bad input
        write_report(_output_folder(args.out), fresh=args.fresh, render_only=args.render_only)
    except MissingResults as err:
        raise UsageError(f"--out {args.out}: {err}") from None
    except ReportIncomplete as err:
        print(f"report incomplete: {err}", file=sys.stderr)
        return 1
    return 0


def cmd_bench(args, session: Session) -> int:
    from ..bench import run_benchmarks, write_benchmarks

    try:
        import scipy  # noqa: F401
    except ImportError:
        raise UsageError("the benchmark compares with scipy: pip install scipy (or the project's [bench] extra)") from None
    out = _output_folder(args.out)
    t0 = time.monotonic()
    write_benchmarks(run_benchmarks(quick=args.quick, progress=lambda s: print(s, file=sys.stderr, flush=True)), out)
    session.emit(f"wrote {out}/BENCHMARKS.md, benchmarks.json and figures/bench-*.png ({time.monotonic() - t0:.0f} s)")
    return 0

"""The commands ``models``, ``threshold``, ``spindown``, ``reference``, ``score``, ``sweep``, ``report``, ``bench``;
each reads its arguments, runs, and hands its output to the session (``trajectory`` is :mod:`.run_command`'s).
Heavy modules are imported inside each command, so that ``--help`` and the listings answer at once."""
from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path

from models.catalogue import ALIASES, BODY_PREFIX, COULOMB_NAMES, ENTRIES

from ..guard import Session
from .arguments import _DECIMAL, RunFailed, UsageError, _decimal, _numeric_pairs, _positive, _positive_int, _shown
from .output import _dumps


# --- the other commands -------------------------------------------------------------------------

def cmd_models(args, session: Session) -> int:
    """The models from :mod:`models.catalogue` (plain data, checked against the derivation by the tests)."""
    records = []
    for e in ENTRIES:
        records.append({
            "model": e.name,
            "title": e.title,
            "equations": list(e.equations),
            "parameters": {name: {"default": default, "range": allowed, "description": text}
                           for name, default, allowed, text in e.parameters},
            "domain": f"{e.domain[0]} < theta < {e.domain[1]}",
            "invariants": list(e.invariants),
            "energy_unit": e.inertia_unit,
            "length_unit": e.length_unit,
        })
    aliases = {name: {"model": model, "params": params} for name, (model, params) in ALIASES.items()}
    coulomb = {name: f"the {name.split('+')[0]} rolling and sliding with Coulomb friction (--friction MU)"
               for name in COULOMB_NAMES}
    if args.format == "json":
        session.emit(_dumps({"models": records, "aliases": aliases, "coulomb": coulomb}))
        return 0
    lines = []
    for r in records:
        lines.append(f"{r['model']}: {r['title']} (equations: {', '.join(r['equations'])})")
        for pname, p in r["parameters"].items():
            lines.append(f"    {pname:<3} default {p['default']:<28} range {p['range']:<12} {p['description']}")
        lines.append(f"    domain {r['domain']}; invariants: {', '.join(r['invariants'])}; lengths in {r['length_unit']}, "
                     f"moments of inertia in {r['energy_unit']}, energies in {r['energy_unit']}/s^2")
    for name, a in aliases.items():
        lines.append(f"{name}: the {a['model']} with {', '.join(f'{k} = {v}' for k, v in a['params'].items())}")
    for name, text in coulomb.items():
        lines.append(f"{name}: {text}")
    lines.append("units: time s, angles rad, lengths in R (or the ball radius a), g/L = 980 s^-2 by default "
                 "(g = 980 cm/s^2, L = 1 cm); in SI: --param g=9.81 with L = 1 m; the normal force N in units of M g, "
                 "M the body's whole mass (2m for the two hurricane balls of mass m)")
    lines.append("next: python -m verify trajectory disk --plot run.png   (a model's default start; "
                 "python -m verify starts lists named starts)")
    session.emit("\n".join(lines))
    return 0


def cmd_starts(args, session: Session) -> int:
    """The named starts: every figure panel's and every reference case's (:mod:`verify.starts`)."""
    from ..starts import DEFAULT_CASES, all_starts  # lazy: 10 ms kept out of --help, models

    starts = all_starts()
    if args.format == "json":
        session.emit(_dumps([{"name": s.name, "kind": s.kind, "model": s.model, "params": s.params, "state": s.state,
                              "t_end": s.t_end, "source": s.source, "note": s.note} for s in starts]))
        return 0
    lines = []
    for kind, heading in (("figure", "figure starts (the report's runs of the paper's captions)"),
                          ("reference", "reference cases (reports/reference: proved and agreeing digits)")):
        group = [s for s in starts if s.kind == kind]
        if not group:
            continue
        lines.append(f"{heading}:")
        for s in group:
            state = ", ".join(f"{k} = {_brief(v)}" for k, v in s.state.items())
            lines.append(f"  {s.name:<24} {s.model:<12} t_end {s.t_end:>4} s  {state}")
    lines.append("a reference case named after a figure (disk-fig5-rhs) is the reference set's own reading of the caption "
                 "(its note says which); the figure starts (fig5-rhs) are the report's runs")
    lines.append("defaults (a model run without --start or --state): "
                 + ", ".join(f"{m} -> {c}" for m, c in DEFAULT_CASES.items()))
    lines.append("next: python -m verify trajectory --start fig5-lhs --output run.csv --plot run.png")
    session.emit("\n".join(lines))
    return 0


def _brief(text: str) -> str:
    """A start value shortened for the listing (the run uses every digit)."""
    try:
        value = float(text)
    except ValueError:
        return text
    return text if len(text) <= 10 else f"{value:.6g}"


def cmd_plot(args, session: Session) -> int:
    """``plot RUN --out FILE``: the picture of a saved run (:mod:`verify.series.plot`)."""
    from ..series.files import RunFileError, read_run  # lazy: numpy (0.25 s) kept out of --help
    from ..series.plot import picture_path, write_plot  # lazy: numpy (0.2 s) kept out of --help

    try:
        out = picture_path(args.out, "--out")
        columns = read_run(args.run_file)
    except RunFileError as err:
        raise UsageError(str(err)) from None
    body = _recorded_body(columns.meta, args.run_file)
    write_plot(columns, out)
    session.emit(f"wrote {out} ({columns.meta.get('model')}{f', the body {body}' if body else ''}, "
                 f"{len(columns.values['t'])} points, {columns.meta.get('outcome')})")
    return 0


def _recorded_body(meta: dict, run_file) -> str | None:
    """The name of the body a run's file records (``trajectory --body``), read back from its exact text and checked
    against its fingerprint and model name, then registered (its name resolves here); None for a model's run."""
    import tomllib  # lazy: tomllib (23 ms) only for 'plot' of a body's run; kept out of --help

    from models.bodies import InvalidBody, body_from_mapping, fingerprint, register  # lazy: sympy, not --help

    recorded = meta.get("body")
    if recorded is None:
        return None
    try:
        body = body_from_mapping(tomllib.loads(recorded["toml"]), f"{run_file}'s body")
    except (KeyError, TypeError, tomllib.TOMLDecodeError, InvalidBody) as err:
        raise UsageError(f"{run_file}: the body it records cannot be read ({err}); allowed: a file written by "
                         "'trajectory --body ... --output'") from None
    if fingerprint(body) != recorded.get("fingerprint") or register(body) != recorded.get("model"):
        raise UsageError(f"{run_file}: the body text it records does not match its fingerprint "
                         f"{str(recorded.get('fingerprint'))[:12]} (the file was edited); re-run the trajectory")
    return body.name


def _body_or_model(args, what: str) -> tuple:
    """(body model or None, the rest of the positionals): ``--body FILE`` or ``body:NAME[@HASH]`` in the model's place."""
    from .body_studies import body_model  # lazy: mpmath (45 ms) kept out of --help

    given = [a for a in (args.model, getattr(args, "motion", None)) if a is not None]
    if args.body is not None:
        if given and given[0].startswith(BODY_PREFIX):
            raise UsageError(f"give the body once: {given[0]} or --body {args.body}")
        return body_model(args.body, "--body"), given
    if given and given[0].startswith(BODY_PREFIX):
        return body_model(given[0], what), given[1:]
    return None, given


def cmd_threshold(args, session: Session) -> int:
    from ..studies.thresholds import bracket, threshold, to_record  # lazy: heyoka, sympy (1 s) kept out of --help

    params = _numeric_pairs(args.param, "param")
    body, rest = _body_or_model(args, "threshold")
    if body is not None or args.theta0 is not None:
        return _body_threshold(args, session, body, rest, params)
    if len(rest) != 2:
        raise UsageError("threshold takes a model and a motion (threshold disk straight-line), or a body and a motion "
                         "(threshold --body FILE.toml straight-line, threshold body:NAME sleeping)")
    args.model, args.motion = rest
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
    unit = " s^-1" if value and rec["threshold"]["name"].endswith("dot0") else ""  # the thresholds are rates
    lines = [f"{rec['model']} {rec['motion']}: {rec['threshold']['name']} = {value + unit if value else 'none'}"
             f"{'  (' + rec['closed_form'] + ')' if rec['closed_form'] else ''}", f"  {rec['method']}"]
    if args.nonlinear_tilt is not None:
        b = rec.get("bracket")
        if b is None:
            lines.append(f"nonlinear bracket at tilt {tilt}: none (no linear threshold to bracket)")
        else:
            lines.append(f"nonlinear bracket at tilt {b['tilt']} rad: {rec['threshold']['name']} in "
                         f"[{b['low']}, {b['high']}]{unit}")
            lines.append(f"  {b['method']}")
    session.emit("\n".join(lines))
    return 0


def _body_threshold(args, session: Session, body, rest: list, params: dict) -> int:
    """``threshold --body FILE MOTION`` / ``threshold body:NAME MOTION`` (:mod:`.body_studies`)."""
    from .body_studies import body_threshold, threshold_text  # lazy: mpmath (45 ms) kept out of --help

    if body is None:
        raise UsageError("--theta0 picks one of a body's steady motions; give a body (--body FILE, body:NAME)")
    if len(rest) != 1:
        raise UsageError(f"threshold of a body takes one motion after it (straight-line, diameter-spin, sleeping); "
                         f"got {len(rest)}: {' '.join(rest) or 'none'}")
    if args.nonlinear_tilt is not None:
        raise UsageError("--nonlinear-tilt is built for the paper's models (disk, ring, hurricane, ...): a body's threshold "
                         "is checked on its full equations by verify/studies/steady_confirm.py (10 % either side)")
    rec = body_threshold(body, rest[0], params, args.theta0)
    session.emit(_dumps(rec) if args.format == "json" else threshold_text(rec))
    return 0


def cmd_spindown(args, session: Session) -> int:
    from ..studies.spindown import spindown, to_record  # lazy: sympy (0.6 s) kept out of --help

    params = _numeric_pairs(args.param, "param")
    theta = _decimal(args.theta, f"--theta {_shown(args.theta)}")
    body, rest = _body_or_model(args, "spindown")
    if len(rest) != (0 if body is not None else 1):
        raise UsageError("spindown takes a model (disk or ring) or a body (--body FILE.toml, body:NAME), and --theta")
    energy = "m R^2/s^2"
    try:
        if body is not None:
            from .body_studies import body_spindown_record  # lazy: mpmath (45 ms) kept out of --help

            rec, energy = body_spindown_record(body, theta, args.family, params), "M L^2/s^2"
        else:
            rec = to_record(spindown(rest[0], theta, args.family, params))
    except ValueError as err:
        raise UsageError(str(err)) from None
    if args.format == "json":
        session.emit(_dumps(rec))
        return 0
    units = {"theta": "rad", "phidot": "s^-1", "psidot": "s^-1", "paper_phidot": "s^-1", "energy": energy}
    session.emit("\n".join(f"{k:<15} {'none (no closed form for this body)' if v is None else v}"
                           f"{' ' + units[k] if k in units and v is not None else ''}" for k, v in rec.items()))
    return 0


def cmd_reference(args, session: Session) -> int:
    from .. import reference  # lazy: heyoka, sympy (1 s) kept out of --help

    directory = Path(args.dir) if args.dir else reference.DIRECTORY
    say = lambda text: print(text, file=sys.stderr, flush=True)  # noqa: E731
    if args.export is None and args.format == "csv":
        raise UsageError("--format csv is for --export; --check prints text or json")
    if args.body is not None:
        args.case = _body_cases(args, directory)
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
            from ..reference.export import export_set  # lazy: heyoka, sympy (1 s) kept out of --help

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


def _body_cases(args, directory) -> list:
    """``reference --check --body NAME``: the names of every case of that body (its rolling and its Coulomb cases)."""
    from ..scoring.casefiles import read_index  # lazy: numpy (0.2 s) kept out of --help
    from .body_studies import body_model  # lazy: mpmath (45 ms) kept out of --help

    if not args.check or args.case:
        raise UsageError("--body is for --check without --case: it checks every case of that body")
    name = body_model(args.body, "--body").name
    try:
        index = read_index(directory)
    except (OSError, ValueError) as err:
        raise UsageError(f"--dir {directory}: no reference set to check ({err})") from None
    cases = [c["name"] for c in index["cases"] if c["model"].split("+")[0] == name]
    if not cases:
        bodies = sorted({c["model"].split("+")[0] for c in index["cases"] if c["model"].startswith("body:")})
        raise UsageError(f"--body {args.body}: the reference set has no case of {name}; bodies with cases: "
                         f"{', '.join(bodies) or 'none'}")
    return cases


def _prove(args, directory, say) -> int:
    """``reference --prove``: each case of <= 10 s (or those named) enclosed, resuming stored proofs."""
    from fractions import Fraction  # lazy: fractions (8 ms) only for 'reference --prove'; kept out of --help

    from ..reference import load_set  # lazy: heyoka, sympy (0.9 s) kept out of --help
    from ..reference.proved import prove_case, settings_of, write_summary  # lazy: 0.9 s kept out of --help

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
    records = [r for r in load_set(directory, args.case)  # the Coulomb cases are agreed only (prove_case says why)
               if args.case or (Fraction(r["t_end"]) <= 10 and "friction" not in r)]
    for record in records:
        proof = prove_case(record, directory=directory, budget=float(budget), until=until,
                           settings=settings_of(int(bits)), progress=say)
        say(f"{record['name']}: proved to t = {proof['times'][-1]} of {record['t_end']}"
            + (f" ({proof['stopped']})" if proof["stopped"] else ""))
        write_summary(directory)
    return 0


def cmd_score(args, session: Session) -> int:
    """``score RUN --case NAME [--min-digits D]``: the table; exit 1 below D or for a partial run."""
    from ..scoring import START_TOLERANCE, score  # lazy: numpy (0.2 s) kept out of --help
    from ..scoring.casefiles import DIRECTORY  # lazy: numpy (0.2 s) kept out of --help

    tol = START_TOLERANCE if args.start_tol is None else float(_positive(args.start_tol, "--start-tol", "1e-9"))
    if not tol < 1:  # a tolerance of a whole scale or more (or one that overflows to inf) checks no start at all
        raise UsageError(f"--start-tol {args.start_tol}: allowed a fraction of each component's scale below 1, "
                         "such as 1e-9")
    minimum = None if args.min_digits is None else float(_decimal(args.min_digits, "--min-digits", "6"))
    try:
        result = score(args.run_file, args.case, directory=Path(args.dir) if args.dir else DIRECTORY, start_tolerance=tol)
    except ValueError as err:  # InvalidRun and an unknown case: bad input
        raise UsageError(str(err)) from None
    record = result.to_record()
    why = None if minimum is None else result.failure(minimum)
    if minimum is not None:
        record["min_digits_required"], record["passed"] = minimum, why is None
    session.emit(_dumps(record) if args.format == "json" else result.table()
                 + ("" if minimum is None else f"\n{'PASS' if why is None else 'FAIL'}: "
                    + (f"at least {minimum:g} digits over the whole case" if why is None else why)))
    if why is not None:
        raise RunFailed(f"score {args.case}: {why}")
    return 0


def cmd_sweep(args, session: Session) -> int:
    from .. import sweep  # lazy: heyoka, sympy (1 s) kept out of --help
    from ..provenance import write_atomic  # lazy: verify.provenance (33 ms) kept out of --help

    try:
        spec = sweep.load(args.spec, store=args.store)
        threads = _positive_int(args.threads, "--threads") if args.threads is not None else None
        if args.plot:
            if args.dask is not None:
                raise UsageError("--plot draws from the store; it does not run anything (drop --dask)")
            if not Path(spec.store).exists():
                raise UsageError(f"no store {spec.store} yet: run 'python -m verify sweep {args.spec}' first")
            from ..sweep.plot import render  # lazy: heyoka, sympy (1 s) kept out of --help

            with sweep.Store(spec) as store:
                rows = store.rows()
            if not rows:
                raise UsageError(f"the store {spec.store} holds no rows yet")
            out = Path(args.out) if args.out else Path(spec.store).with_suffix(".png")
            if out.is_dir():
                raise UsageError(f"--out {args.out} is a folder; allowed: a file name for the PNG, such as "
                                 f"{out / Path(spec.store).with_suffix('.png').name}")
            if out.suffix.lower() != ".png":
                raise UsageError(f"--out {args.out}: the sweep's map is drawn as PNG; allowed: a file name ending "
                                 f"in .png, such as {out.with_suffix('.png')}")
            _output_folder(str(out.parent))
            write_atomic(out, render(spec, rows))
            session.emit(f"wrote {out} ({len(rows)} of {spec.n_points} trajectories)")
            return 0
        session.interrupt_note = (f"the store {args.store or spec.store} keeps the finished chunks; "
                                  "rerun the same command to resume")
        from ..studies.orbits import senses  # lazy: only the sweep command reads orbits; start-up imports no study

        result = sweep.run_sweep(spec, dask=args.dask, threads=threads, progress=not args.quiet, yes=args.yes,
                                 senses=senses)
    except (sweep.SpecError, sweep.StoreError, sweep.ClusterError) as err:
        raise UsageError(str(err)) from None
    session.emit(f"{spec.name}: {result.rows} of {spec.n_points} trajectories in {result.store} "
                 f"({result.chunks_run} chunks run, {result.chunks_skipped} already there; {result.where}; "
                 f"{result.seconds:.1f} s)")
    return 0


def _output_folder(folder: str) -> str:
    from ..provenance import writable_folder  # lazy: verify.provenance (33 ms) kept out of --help

    try:
        writable_folder(folder)
    except ValueError as err:
        raise UsageError(f"--out: {err}") from None
    return folder


def cmd_report(args, session: Session) -> int:
    from ..report.write import MissingResults, ReportIncomplete, read_results, write_report  # lazy: not --help

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


def cmd_engines(args, session: Session) -> int:
    """``engines``: the leaderboard (verify.leaderboard): every engine adapter on the reference cases."""
    from ..leaderboard import (CASES, adapters, merge_boards, rewrite_figure, run_board,  # lazy: 27 ms, not for --help
                               write_board)

    if args.render_only:
        if not (Path(args.out) / "engines.json").exists():
            raise UsageError(f"--render-only: no {Path(args.out) / 'engines.json'} yet; run 'make engines' first")
        session.emit(f"wrote {rewrite_figure(args.out)} from {Path(args.out) / 'engines.json'}")
        return 0
    found = adapters()
    for name in args.engine or ():
        if name not in found:
            raise UsageError(f"--engine {name!r}: no adapter examples/engines/{name}_adapter.py; allowed: "
                             f"{', '.join(found) or 'none found'}")
    known = dict(CASES)
    for name in args.case or ():
        if name not in known:
            raise UsageError(f"--case {name!r}: not a case of the board; allowed: {', '.join(known)}")
    out = _output_folder(args.out)
    if args.case:
        cases = tuple((c, t) for c, t in CASES if c in args.case)
    else:
        cases = CASES[:1] if args.quick else CASES
    board = run_board(args.engine, cases, progress=lambda s: print(s, file=sys.stderr, flush=True))
    existing = Path(out) / "engines.json"
    if args.case and existing.exists():  # a rerun of some cases: the board's other rows stay
        board = merge_boards(json.loads(existing.read_text()), board)
    written = write_board(board, out)
    session.emit(f"wrote {', '.join(str(p) for p in written)} ({len(board['rows'])} runs); "
                 "next: make report (its Engines section reads them)")
    return 0


def cmd_bench(args, session: Session) -> int:
    from ..bench import run_benchmarks, write_benchmarks  # lazy: heyoka, sympy (0.9 s) kept out of --help

    try:
        import scipy  # noqa: F401  # lazy: scipy (0.2 s), optional: only to tell whether it is installed
    except ImportError:
        raise UsageError("the benchmark compares with scipy: pip install scipy (or the project's [bench] extra)") from None
    out = _output_folder(args.out)
    t0 = time.monotonic()
    write_benchmarks(run_benchmarks(quick=args.quick, progress=lambda s: print(s, file=sys.stderr, flush=True)), out)
    session.emit(f"wrote {out}/BENCHMARKS.md, benchmarks.json and figures/bench-*.png ({time.monotonic() - t0:.0f} s)")
    return 0

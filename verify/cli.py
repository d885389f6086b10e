"""Command line: ``python -m verify {trajectory,models,report} ...``.

Bad input exits with status 2 and one line on stderr naming the bad value and what is
allowed; a failed integration exits with status 1.
"""
from __future__ import annotations

import argparse
import json
import math
import sys

from models import ALL_NAMES, get_model, sources
from models.symbols import STATE_NAMES

from .integrate import IntegrationError, solve
from .precision import ALLOWED, parse_precision


class UsageError(Exception):
    """Bad input on the command line (exit status 2)."""


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
    """initial, final and the drifts of one invariant (verify.invariants.InvariantTrace); an
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
    lines += [f"  {n:<12} {v['initial']}  {v['final']}  {v['max_abs_drift']:.3e}  {_num(v['max_rel_drift'], '.3e')}"
              f"  {_num(v['max_drift_vs_terms_in_eps'], '.3g')}"
              for n, v in record["invariants"].items()]
    return "\n".join(lines)


def _num(x, fmt: str) -> str:
    return "n/a" if x is None else format(x, fmt)


def cmd_trajectory(args) -> int:
    try:
        precision = parse_precision(args.precision)
    except ValueError as err:
        raise UsageError(str(err)) from None
    if args.model not in ALL_NAMES:
        raise UsageError(f"unknown model {args.model!r}; allowed: {', '.join(ALL_NAMES)}")
    if args.equations not in sources(args.model):
        raise UsageError(f"--equations {args.equations} for model {args.model!r}; allowed: {', '.join(sources(args.model))}")
    try:
        sol = solve(
            args.model, args.t_end, _pairs(args.state, "state"), _pairs(args.param, "param"),
            precision=precision, equations=args.equations, tol=args.tol, high_accuracy=args.high_accuracy,
        )
    except ValueError as err:
        raise UsageError(str(err)) from None
    record = trajectory_record(sol)
    print(json.dumps(record, indent=2) if args.format == "json" else _text(record))
    return 0


def cmd_models(args) -> int:
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
        print(json.dumps(records, indent=2))
        return 0
    for r in records:
        print(f"{r['model']}: {r['title']} (equations: {', '.join(r['equations'])})")
        for pname, p in r["parameters"].items():
            print(f"    {pname:<3} default {p['default']:<28} range {p['range']:<12} {p['description']}")
        print(f"    domain {r['domain']}; invariants: {', '.join(r['invariants'])}; energy per {r['energy_unit']}")
    return 0


def cmd_threshold(args) -> int:
    from .studies.thresholds import bracket, threshold, to_record

    params = _pairs(args.param, "param")
    try:
        result = threshold(args.model, args.motion, params)
        nonlinear = None
        if args.nonlinear_tilt is not None:
            try:
                tilt = float(args.nonlinear_tilt)
            except ValueError:
                raise ValueError(f"--nonlinear-tilt {args.nonlinear_tilt!r} is not a number; allowed: (0, 0.1)") from None
            if not 0 < tilt < 0.1:
                raise ValueError(f"--nonlinear-tilt {args.nonlinear_tilt} must lie in (0, 0.1)")
            nonlinear = (args.nonlinear_tilt, bracket(args.model, args.motion, args.nonlinear_tilt, params))
        rec = to_record(result, nonlinear)
    except ValueError as err:
        raise UsageError(str(err)) from None
    if args.format == "json":
        print(json.dumps(rec, indent=2))
    else:
        value = rec["threshold"]["value"]
        print(f"{rec['model']} {rec['motion']}: {rec['threshold']['name']} = {value if value else 'none'}"
              f"{'  (' + rec['closed_form'] + ')' if rec['closed_form'] else ''}\n  {rec['method']}")
    return 0


def cmd_spindown(args) -> int:
    from .studies.spindown import spindown, to_record

    try:
        rec = to_record(spindown(args.model, args.theta, args.family, _pairs(args.param, "param")))
    except ValueError as err:
        raise UsageError(str(err)) from None
    if args.format == "json":
        print(json.dumps(rec, indent=2))
    else:
        print("\n".join(f"{k:<15} {v}" for k, v in rec.items()))
    return 0


def cmd_reference(args) -> int:
    from pathlib import Path

    from . import reference

    directory = Path(args.dir) if args.dir else reference.DIRECTORY
    say = lambda text: print(text, file=sys.stderr, flush=True)  # noqa: E731
    try:
        if args.make:
            if args.precision is not None:
                raise UsageError("--precision is for --check; --make always runs mp:128 and mp:256")
            jobs = _positive_int(args.jobs, "--jobs")
            import time

            t0 = time.monotonic()
            records = reference.make_set(args.case, jobs=jobs, directory=directory, progress=say)
            say(f"wrote {len(records)} case(s) to {directory} in {time.monotonic() - t0:.0f} s")
            return 0
        checks = reference.check_set(args.precision or "double", args.case, directory, progress=say)
    except ValueError as err:
        raise UsageError(str(err)) from None
    if args.format == "json":
        print(json.dumps([c.to_record() for c in checks], indent=2))
    else:
        print(reference.render_checks(checks))
    failed = [c.case for c in checks if not c.ok]
    if failed:
        print(f"error: {len(failed)} case(s) out of bound: {', '.join(failed)}", file=sys.stderr)
        return 1
    return 0


def _positive_int(text, what: str) -> int:
    try:
        value = int(text)
    except (TypeError, ValueError):
        raise UsageError(f"{what} {text!r} is not an integer; allowed: 1, 2, ...") from None
    if value < 1:
        raise UsageError(f"{what} {text} must be at least 1")
    return value


def cmd_sweep(args) -> int:
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
            _output_folder(str(out.parent))
            write_atomic(out, render(spec, rows))
            print(f"wrote {out} ({len(rows)} of {spec.n_points} trajectories)")
            return 0
        result = sweep.run_sweep(spec, dask=args.dask, threads=threads, progress=not args.quiet)
    except (sweep.SpecError, sweep.StoreError, sweep.ClusterError) as err:
        raise UsageError(str(err)) from None
    print(f"{spec.name}: {result.rows} of {spec.n_points} trajectories in {result.store} "
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


def cmd_report(args) -> int:
    from .report import write_report

    write_report(_output_folder(args.out), bench=not args.no_bench)
    return 0


def cmd_bench(args) -> int:
    import time

    from .bench import run_benchmarks, write_benchmarks

    try:
        import scipy  # noqa: F401
    except ImportError:
        raise UsageError("the benchmark compares with scipy: pip install scipy (or the project's [bench] extra)") from None
    out = _output_folder(args.out)
    t0 = time.monotonic()
    write_benchmarks(run_benchmarks(quick=args.quick, progress=lambda s: print(s, file=sys.stderr, flush=True)), out)
    print(f"wrote {out}/BENCHMARKS.md, benchmarks.json and figures/bench-*.png ({time.monotonic() - t0:.0f} s)")
    return 0


def parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m verify", description=__doc__.splitlines()[0])
    sub = ap.add_subparsers(dest="command", required=True)

    t = sub.add_parser("trajectory", help="integrate one model from one state")
    t.add_argument("model", help=f"one of: {', '.join(ALL_NAMES)}")
    t.add_argument("--equations", default="derived", help="derived (default) or paper")
    t.add_argument("--param", action="append", metavar="NAME=VALUE", help="a parameter (repeatable)")
    t.add_argument("--state", action="append", metavar="NAME=VALUE",
                   help=f"an initial value, unset ones are 0 (names: {', '.join(STATE_NAMES)})")
    t.add_argument("--t-end", required=True, help="final time in seconds")
    t.add_argument("--precision", default="double", help=ALLOWED)
    t.add_argument("--tol", default=None, help="Taylor tolerance (default: the precision's epsilon)")
    t.add_argument("--high-accuracy", action="store_true",
                   help="heyoka's compensated summation: energy error ~ t^0.5 over 1e6 steps (python -m verify bench)")
    t.add_argument("--format", choices=("json", "text"), default="text")
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
    sw.set_defaults(run=cmd_sweep)

    r = sub.add_parser("report", help="run the verification and write reports/")
    r.add_argument("--out", default="reports", help="output folder (default: reports)")
    r.add_argument("--no-bench", action="store_true", help="skip the benchmarks (BENCHMARKS.md is left as it is)")
    r.set_defaults(run=cmd_report)

    b = sub.add_parser("bench", help="benchmarks: work against precision, energy error, sweep throughput, JIT cost")
    b.add_argument("--out", default="reports", help="output folder (default: reports)")
    b.add_argument("--quick", action="store_true", help="small sizes (for trying the command; not for the report)")
    b.set_defaults(run=cmd_bench)
    return ap


def main(argv=None) -> int:
    args = parser().parse_args(argv)
    try:
        return args.run(args)
    except UsageError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    except (IntegrationError, RuntimeError) as err:  # a failed run or a study that found no root
        print(f"error: {err}", file=sys.stderr)
        return 1

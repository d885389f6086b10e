"""The argument parser: the commands and their options; ``--opt -VALUE`` and ``--debug`` anywhere on the line."""
from __future__ import annotations

import argparse

from .arguments import UsageError
from .commands import (cmd_bench, cmd_engines, cmd_models, cmd_plot, cmd_reference, cmd_report, cmd_score, cmd_spindown, cmd_starts,
                       cmd_sweep, cmd_threshold)
from .animate_command import add_parser as add_animate_parser
from .figure_command import add_parser as add_figure_parser
from .run_command import add_trajectory_parser
from ..studies.tippe.command import add_parser as add_tippe_top_parser

#: --help's first line
DESCRIPTION = ("Bodies rolling on a plane, verified.  First steps: 'python -m verify trajectory disk --plot run.png', "
               "'python -m verify starts', 'python -m verify figure --list'.")

# --- the parser -------------------------------------------------------------------------------

class _Parser(argparse.ArgumentParser):
    """argparse, with its errors as one line (UsageError) instead of a usage block and exit."""

    def error(self, message):
        raise UsageError(f"{message} (see '{self.prog} --help')")


def parser() -> argparse.ArgumentParser:
    ap = _Parser(prog="python -m verify", description=DESCRIPTION)
    ap.add_argument("--debug", action="store_true",
                    help="show the Python traceback of an unexpected error (may be given anywhere on the line)")
    sub = ap.add_subparsers(dest="command", required=True)

    add_trajectory_parser(sub)
    add_figure_parser(sub)
    add_animate_parser(sub)
    add_tippe_top_parser(sub)

    pl = sub.add_parser("plot", help="draw a saved run (a file of 'trajectory --output')")
    pl.add_argument("run_file", metavar="RUN", help="RUN.csv, RUN.json or RUN.npz written by 'trajectory --output'")
    pl.add_argument("--out", required=True, metavar="FILE", help="the picture: FILE.png, FILE.svg or FILE.pdf")
    pl.set_defaults(run=cmd_plot)

    st = sub.add_parser("starts", help="list the named starts (--start NAME): every figure's and reference case's")
    st.add_argument("--format", choices=("json", "text"), default="text")
    st.set_defaults(run=cmd_starts)

    m = sub.add_parser("models", help="list the models, their parameters and invariants")
    m.add_argument("--format", choices=("json", "text"), default="text")
    m.set_defaults(run=cmd_models)

    th = sub.add_parser("threshold", help="linear stability threshold of a steady motion (a model's or a body file's)",
                        description="Examples: 'threshold disk straight-line', 'threshold body:rounded-coin diameter-spin', "
                                    "'threshold --body my-body.toml sleeping --theta0 pi'.")
    th.add_argument("model", nargs="?", default=None,
                    help="a model (disk, sliding-disk, ring, hurricane, gyroscope) or body:NAME (or give --body FILE)")
    th.add_argument("motion", nargs="?", default=None,
                    help="diameter-spin, straight-line, precession or sleeping (as the model or body has them)")
    th.add_argument("--body", default=None, metavar="FILE",
                    help="a body file (any path), a shipped body's name or body:NAME@HASH, in place of the model: the "
                         "generic steady motions of verify/studies/steady_bodies.py (docs/bodies.md)")
    th.add_argument("--theta0", default=None, metavar="TILT",
                    help="a body with two motions of one kind (sleeping at 0 and pi): the steady tilt of the one wanted")
    th.add_argument("--param", action="append", metavar="NAME=VALUE")
    th.add_argument("--nonlinear-tilt", default=None, metavar="TILT",
                    help="also bracket the threshold by bisection on the full equations with this tilt (e.g. 1e-6)")
    th.add_argument("--format", choices=("json", "text"), default="text")
    th.set_defaults(run=cmd_threshold)

    sd = sub.add_parser("spindown", help="exact steady spin-down state at a tilt, against Eq. 45 / Eq. 61")
    sd.add_argument("model", nargs="?", default=None, help="disk or ring, or body:NAME (or give --body FILE)")
    sd.add_argument("--body", default=None, metavar="FILE",
                    help="a body file (any path), a shipped body's name or body:NAME@HASH, in place of the model "
                         "(the paper's closed form shown where the body is the disk's or the ring's)")
    sd.add_argument("--theta", required=True)
    sd.add_argument("--family", default="cm-at-rest", help="cm-at-rest (default) or zero-vertical-spin")
    sd.add_argument("--param", action="append", metavar="NAME=VALUE")
    sd.add_argument("--format", choices=("json", "text"), default="text")
    sd.set_defaults(run=cmd_spindown)

    ref = sub.add_parser("reference", help="make or check the reference trajectories (reports/reference/)")
    job = ref.add_mutually_exclusive_group(required=True)
    job.add_argument("--make", action="store_true", help="compute the set at mp:128 and mp:256 (tens of minutes)")
    job.add_argument("--check", action="store_true", help="re-integrate every case and compare with the agreeing digits")
    job.add_argument("--prove", action="store_true",
                     help="enclose the cases of <= 10 s in proved balls (verify/proof; minutes to hours; resumes)")
    job.add_argument("--export", default=None, metavar="DIR",
                     help="write every case to DIR in the Euler and the rotation-matrix forms, with a README "
                          "(--format csv or json)")
    ref.add_argument("--precision", default=None,
                     help="for --check: double (default), long, quad or mp:BITS; for --prove: mp:BITS (default mp:128)")
    ref.add_argument("--until", default=None, metavar="T",
                     help="for --prove: enclose up to this grid time (default: each case's end)")
    ref.add_argument("--budget", default=None, metavar="SECONDS",
                     help="for --prove: wall-clock seconds per case for this run (default: none); the next run resumes")
    ref.add_argument("--case", action="append", metavar="NAME", help="only this case (repeatable)")
    ref.add_argument("--body", default=None, metavar="NAME",
                     help="for --check: every case of this body (a shipped body's name, body:NAME or its file)")
    ref.add_argument("--jobs", default=None, help="for --make: processes (default 2)")
    ref.add_argument("--dir", default=None, help="the set's folder (default: reports/reference)")
    ref.add_argument("--format", choices=("json", "text", "csv"), default=None,
                     help="--check: text (default) or json; --export: csv or json")
    ref.set_defaults(run=cmd_reference)

    sc = sub.add_parser("score", help="score another simulator's run of a reference case (digits, energy, constraints)")
    sc.add_argument("run_file", metavar="RUN", help="a CSV or JSON file: t and the Euler state, or a rotation matrix/quaternion with the "
                                "centre of mass's position and velocity and the angular velocity (verify.frames)")
    sc.add_argument("--case", required=True, help="the reference case (reports/reference/index.json)")
    sc.add_argument("--dir", default=None, help="the reference set's folder (default: reports/reference)")
    sc.add_argument("--start-tol", default=None,
                    help="how closely the start must match the case, as a fraction of each component's own scale "
                         "(default 1e-12; a looser one is said in the verdict)")
    sc.add_argument("--min-digits", default=None, metavar="D",
                    help="exit 1 unless the run agrees to at least D digits over the whole case (for CI); a run that "
                         "stops before the case's end never passes")
    sc.add_argument("--format", choices=("json", "text"), default="text")
    sc.set_defaults(run=cmd_score)

    sw = sub.add_parser("sweep", help="run (or resume) a parameter sweep described by a TOML file")
    sw.add_argument("spec", help="the sweep's TOML file, or a shipped spec by name (e.g. disk-diameter-spin)")
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
    r.add_argument("--fresh", action="store_true", help="recompute every job, ignoring the cache (.report-cache/)")
    r.add_argument("--render-only", action="store_true",
                   help="compute nothing: render REPORT.md and report.html from the folder's results.json")
    r.set_defaults(run=cmd_report)

    en = sub.add_parser("engines", help="run the other physics engines' adapters on the reference cases and score "
                                        "them (reports/engines.json; minutes to an hour)")
    en.add_argument("--out", default="reports", help="output folder (default: reports)")
    en.add_argument("--engine", action="append", metavar="NAME", help="only this adapter (repeatable), e.g. mujoco")
    en.add_argument("--quick", action="store_true", help="the disk case only")
    en.add_argument("--case", action="append", metavar="NAME",
                    help="only this case of the board (repeatable), e.g. coin-coulomb-skid-1; its rows replace the "
                         "same rows of an existing engines.json, the others are kept")
    en.add_argument("--render-only", action="store_true", help="redraw figures/engines.png from engines.json, run nothing")
    en.set_defaults(run=cmd_engines)

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

"""``python -m verify figure N [--side lhs|rhs|both] [--out DIR] [--format text|json]`` and ``figure --list``.

One paper figure (Figs. 1-20): the caption's words, the suite's verdict on each (from the same
evaluation and drawing as the report, :mod:`verify.paper_figures`), checked against
reports/results.json, and the regenerated figure written to ``DIR/fig-NN.png``
(``fig-NN-lhs.png`` with ``--side``).  Exit 1 when a computed verdict differs from the stored one.
This module imports nothing heavy, so ``figure --list`` answers at once.
"""
from __future__ import annotations

import json
import os
from pathlib import Path

from .arguments import RunFailed, UsageError, _shown


def add_parser(subparsers) -> None:
    """Register ``figure`` on the command line's subparsers."""
    f = subparsers.add_parser("figure", help="one paper figure: its captions' verdicts and the regenerated figure")
    f.add_argument("number", nargs="?", default=None, metavar="N", help="the figure, 1 to 20")
    f.add_argument("--list", action="store_true", help="every figure with its claims and verdicts (from results.json)")
    f.add_argument("--side", default=None, help="lhs, rhs or both (default: both): one panel's runs and claims")
    f.add_argument("--out", default=None, metavar="DIR",
                   help="an existing folder for fig-NN.png (default: the current folder)")
    f.add_argument("--format", choices=("json", "text"), default="text")
    f.set_defaults(run=cmd_figure)


def _out_folder(value) -> Path:
    """--out as an existing, writable folder (never created: a typo must not make a new folder)."""
    folder = Path("." if value is None else value)
    if not folder.exists():
        raise UsageError(f"--out {_shown(value)}: no such folder; allowed an existing folder")
    if not folder.is_dir():
        raise UsageError(f"--out {_shown(value)}: a file, not a folder; allowed an existing folder")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise UsageError(f"--out {_shown(value)}: not writable; allowed a writable folder")
    return folder


def cmd_figure(args, session) -> int:
    from .. import paper_figures as pf  # lazy: the claims' index (35 ms) only for 'figure'; kept out of --help

    if args.list:
        if args.number is not None or args.side is not None or args.out is not None:
            raise UsageError("figure --list takes no figure number, --side or --out (only --format)")
        try:
            listing = pf.figure_list()
        except ValueError as err:  # results.json or the paper is not what it should be
            raise RunFailed(str(err)) from None
        session.emit(json.dumps(pf.list_record(listing), indent=2) if args.format == "json" else pf.list_text(listing))
        return 0
    if args.number is None:
        raise UsageError(f"figure: give a figure number 1 to {pf.N_FIGURES}, or --list")
    try:
        number = pf.check_figure_number(args.number)
    except ValueError as err:
        raise UsageError(str(err)) from None
    if args.side is not None and args.side not in pf.SIDE_CHOICES:
        raise UsageError(f"--side {_shown(args.side)}: allowed {', '.join(pf.SIDE_CHOICES)}")
    folder = _out_folder(args.out)
    try:
        side = pf.check_side(number, args.side)
    except ValueError as err:
        raise UsageError(f"--side {_shown(args.side)}: {str(err).split(': ', 1)[1]}") from None
    try:
        pf.read_results()  # a malformed results.json: one line, before the figure's runs
    except ValueError as err:
        raise RunFailed(str(err)) from None
    fig = pf.make_figure(number, side)
    written = _write(fig, folder)
    nxt = pf.next_step(fig)
    if args.format == "json":
        record = {"figure": fig.number, "title": fig.title, "side": fig.side, "has_simulation": fig.has_simulation,
                  "claims": list(fig.records), "stored_verdicts": fig.stored,
                  "mismatches": [{"id": i, "computed": c, "results_json": s} for i, c, s in fig.mismatches],
                  "images": [{"file": str(p), "alt": img.alt} for p, img in zip(written, fig.images)],
                  "results_file": fig.results_file, "note": fig.note, "next": nxt}
        session.emit(json.dumps(record, indent=2))
    else:
        lines = [pf.figure_text(fig)]
        lines += [f"wrote {p}" for p in written]
        lines.append(nxt)
        session.emit("\n".join(lines))
    if fig.mismatches:
        said = "; ".join(f"{i} computed {c}, results.json {s}" for i, c, s in fig.mismatches)
        raise RunFailed(f"Fig. {number}: verdicts differ from {fig.results_file}: {said} "
                        "(a report out of date, or a check that does not decide the same way twice)")
    return 0


def _write(fig, folder: Path) -> list:
    """Write each image of ``fig`` atomically into ``folder``; the paths written."""
    from ..provenance import write_atomic  # lazy: verify.provenance (70 ms) kept out of --help

    paths = []
    for img in fig.images:
        path = folder / img.filename
        write_atomic(path, img.data)
        paths.append(path)
    return paths

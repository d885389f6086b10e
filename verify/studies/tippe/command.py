"""``python -m verify tippe-top``: the tippe top's thresholds and its runs under both friction laws."""
from __future__ import annotations

import json


def add_parser(sub) -> None:
    p = sub.add_parser("tippe-top", help="the tippe top under the smooth law and exact Coulomb friction: thresholds, "
                                         "runs, verdicts (docs/tippe-top.md)")
    p.add_argument("--quick", action="store_true", help="two slip scales and 10 s runs (about 20 s) instead of eight "
                                                        "and 40 s (about 80 s)")
    p.add_argument("--format", choices=("json", "text"), default="text")
    p.set_defaults(run=cmd_tippe_top)


def cmd_tippe_top(args, session) -> int:
    from . import runs  # lazy: sympy, heyoka (0.6 s): not --help (the parser imports this module)

    result = runs.study(quick=args.quick)
    session.emit(json.dumps(result, indent=1) if args.format == "json" else runs.text(result))
    return 0

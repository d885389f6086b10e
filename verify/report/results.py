"""results.json from the jobs' outcomes: the single source of every number the report shows.

:func:`assemble` puts each job's data where the report reads it (claims in the registry's order,
the conservation rows, the studies, the reference checks), builds the summary from them, and
names what failed.  Wall times stay out (timing.json): the same sources on the same versions
and CPU give the same bytes.
"""
from __future__ import annotations

from ..claims import all_claims, missing
from ..provenance import provenance
from ..reference.proved import INDEX_FORMAT, proved_directory
from ..reference.store import read_index, read_json
from ..studies.conservation import PRECISIONS
from ..studies.spindown import PRECISIONS as SPINDOWN_PRECISIONS, REFERENCE as SPINDOWN_REFERENCE
from .summary import build as build_summary

#: Every precision a number of the report comes from: the conservation table (double, quad),
#: the variational check (double, quad), the spin-down precision study and its reference, the
#: reference checks (double, long, quad).
REPORT_PRECISIONS = ("double", "long", "quad", "mp:128", "mp:256")


def _precisions() -> tuple:
    return PRECISIONS + SPINDOWN_PRECISIONS + (SPINDOWN_REFERENCE,) + REPORT_PRECISIONS


def assemble(outcomes: dict) -> dict:
    """results.json as a dict, from :func:`~.runner.run_jobs`' outcomes (job name -> Outcome)."""
    def data(prefix):
        return [o.data for name, o in outcomes.items() if name.startswith(prefix) and o.status != "failed"]

    def one(name):
        o = outcomes.get(name)
        return None if o is None or o.status == "failed" else o.data

    by_id = {rec["id"]: rec for records in data("claims/") for rec in records}
    claims = [by_id[c.id] for c in all_claims() if c.id in by_id]
    retro = {name.split("/", 1)[1]: o.data for name, o in outcomes.items()
             if name.startswith("retrograde/") and o.status != "failed"}
    checks = {}
    for name, o in outcomes.items():
        if name.startswith("reference/") and o.status != "failed":
            checks.setdefault(name.split("/")[1], []).extend(o.data)
    def by_last(prefix):
        return {name.rsplit("/", 1)[1]: o.data for name, o in outcomes.items()
                if name.startswith(prefix) and o.status != "failed"}

    friction = {"figures": [row for rows in data("friction/figures/") for row in rows],
                "reference": one("friction/reference"), "steady": one("friction/steady"),
                "slip": by_last("friction/slip/"), "coulomb": one("friction/coulomb")}
    studies = {"thresholds": [row for rows in data("thresholds/") for row in rows], "captions": one("studies/captions"),
               "spindown": one("studies/spindown"), "precision": one("studies/precision"), "maps": data("maps/"),
               "dissipation": one("dissipation"), "retrograde": retro,
               "reference": {"index": read_index(), "checks": checks, "proved": _proved_summary()},
               "friction": friction, "bodies": one("bodies"),
               "body_thresholds": one("bodies/thresholds"), "tippe_top": one("tippe-top")}
    failures = [{"job": name, "error": o.error} for name, o in outcomes.items() if o.status == "failed"]
    eqs, figs = missing()
    out = {"summary": None, "claims": claims, "conservation": [row for rows in data("conservation/") for row in rows],
           "studies": studies, "not_covered": {"equations": eqs, "figures": figs},
           "figures": [{"file": img.filename, "alt": img.alt} for o in outcomes.values() for img in o.images],
           "failures": failures, "provenance": provenance(_precisions())}
    try:
        out["summary"] = build_summary(claims, studies)
    except (KeyError, TypeError, IndexError, ValueError) as err:  # a job it reads failed: say so, keep the rest
        failures.append({"job": "summary", "error": f"{type(err).__name__}: {err} (a job it reads failed)"})
    return out


def _proved_summary():
    """The proved enclosures' index (reports/reference/proved/index.json), or None where none were made."""
    path = proved_directory() / "index.json"
    if not path.exists():
        return None
    # the wall times stay in the proofs' own index: results.json carries none (same command, same bytes)
    proofs = read_json(path, INDEX_FORMAT, "no proofs' index {path}")["proofs"]
    return [{k: v for k, v in row.items() if k != "wall_seconds"} for row in proofs]

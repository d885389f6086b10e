"""The paper's twenty figures, one at a time: their claims, the suite's verdicts, the regenerated image.

The paper's figures are lost; only their captions remain.  :func:`figure_list` lists every figure
(Figs. 1-20) with its title (the caption's opening words), its claims (every claim whose source
starts with ``Fig. N``) and the verdicts the report stored in reports/results.json, and whether the
figure has a run the suite regenerates (:mod:`verify.figure_starts`).  It reads two files and
imports nothing heavy, so ``python -m verify figure --list`` answers at once.

:func:`make_figure` evaluates a figure's claims through the same :meth:`Claim.evaluate
<verify.claims.base.Claim.evaluate>` the report uses and draws the figure with the same
:func:`verify.report.figures.render`, so this module and the report's figures come from one piece
of code; it also compares each verdict with the one results.json holds (a report out of date, or
a check that does not give the same verdict twice, must not pass silently).
"""
from __future__ import annotations

import json
import re
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Optional

import verify

from .claims import all_claims
from .claims.base import NOT_CHECKABLE, PAPER_FILE
from .figure_starts import figures_with_runs, panel_sides, starts_of
from .unicode_math import plain

N_FIGURES = 20
#: The report's own data (``make report`` writes it): verdicts are read from here.
RESULTS_FILE = Path(verify.__file__).parents[1] / "reports" / "results.json"
#: How to get results.json when it is missing.
HOW_TO_REPORT = "make report (or python -m verify report)"
SIDE_CHOICES = ("lhs", "rhs", "both")
_TITLE_CHARS = 90


def figure_of(source: str) -> Optional[int]:
    """The figure number a claim's ``source`` names first (``"Fig. 11 RHS (angle)"`` -> 11), else None."""
    m = re.match(r"Fig\. (\d+)\b", source)
    return int(m.group(1)) if m else None


def side_of(source: str) -> Optional[str]:
    """The panel a figure claim's ``source`` names (``"lhs"`` or ``"rhs"``), or None for the whole figure."""
    m = re.search(r"\b(LHS|RHS)\b", source)
    return m.group(1).lower() if m else None


def figure_titles(paper: Path = PAPER_FILE) -> dict:
    """Figure number -> its title: the caption's first sentence (``Figure N: ...`` in the paper),
    cut at a word boundary near 90 characters."""
    titles = {}
    for m in re.finditer(r"^Figure (\d+): (.+)$", paper.read_text(encoding="utf-8"), re.M):
        text = re.split(r"(?<!Eq)(?<!Eqs)(?<!Fig)(?<!FIG)(?<! al)\.\s", m.group(2).strip(), maxsplit=1)[0].rstrip(". ")
        text = plain(text)  # the math in Unicode before the cut: a cut never splits a $...$
        if len(text) > _TITLE_CHARS:
            text = text[:_TITLE_CHARS].rsplit(" ", 1)[0] + " ..."
        titles[int(m.group(1))] = text
    missing = sorted(set(range(1, N_FIGURES + 1)) - set(titles))
    if missing:
        raise ValueError(f"{paper}: no caption 'Figure N: ...' found for figure(s) {missing}")
    return titles


def read_results(path: Optional[Path] = None) -> Optional[dict]:
    """Claim id -> its results.json record (default file: :data:`RESULTS_FILE`), or None when the file
    does not exist (a malformed file raises)."""
    path = Path(RESULTS_FILE if path is None else path)
    if not path.exists():
        return None
    try:
        claims = json.loads(path.read_text(encoding="utf-8"))["claims"]
    except (ValueError, KeyError, TypeError) as err:
        raise ValueError(f"{path}: not the report's results.json ({err}); rerun {HOW_TO_REPORT}") from None
    return {c["id"]: c for c in claims}


@dataclass(frozen=True)
class ClaimEntry:
    """One claim of a figure as the list shows it: ``verdict`` is results.json's (None without it)."""

    id: str
    source: str
    verdict: Optional[str]


@dataclass(frozen=True)
class FigureEntry:
    """One paper figure: its title, its claims, its panel sides and whether the suite regenerates a run."""

    number: int
    title: str
    claims: tuple
    has_simulation: bool
    sides: tuple


@dataclass(frozen=True)
class FigureList:
    """Every figure (Figs. 1-20); ``note`` says where the verdicts come from, or how to get them."""

    figures: tuple
    results_file: Optional[str]
    note: str


def figure_list(results_path: Optional[Path] = None) -> FigureList:
    """Every figure 1..20 with its title, claims and verdicts (from results.json) and whether it has a run.

    Without results.json the claims are not known either (they would need the claim modules, which
    are slow to import): the figures are listed with their titles and runs, and the note says how
    to get the verdicts.
    """
    results_path = Path(RESULTS_FILE if results_path is None else results_path)
    titles, results = figure_titles(), read_results(results_path)
    simulated = set(figures_with_runs())
    figures = []
    for n in range(1, N_FIGURES + 1):
        records = [r for r in (results or {}).values() if figure_of(r["source"]) == n]
        claims = tuple(ClaimEntry(r["id"], r["source"], r["verdict"]) for r in records)
        sides = tuple(s for s in ("lhs", "rhs") if s in panel_sides(n) or any(side_of(c.source) == s for c in claims))
        figures.append(FigureEntry(n, titles[n], claims, n in simulated, sides))
    if results is None:
        note = f"no {results_path}: verdicts not listed; run {HOW_TO_REPORT} to compute them"
        return FigureList(tuple(figures), None, note)
    return FigureList(tuple(figures), str(results_path), f"verdicts from {results_path}")


def list_text(listing: FigureList) -> str:
    """The list as text: one header line a figure, one line a claim, the note last."""
    lines = []
    for f in listing.figures:
        run = f"run ({', '.join(f.sides) or 'one panel'})" if f.has_simulation else "no run"
        lines.append(f"Fig. {f.number:2d}  [{run}]  {f.title}")
        width = max((len(c.source) for c in f.claims), default=0)
        lines += [f"    {c.source:<{width}}  {c.verdict or '-':<13}  {c.id}" for c in f.claims]
    lines.append(listing.note)
    return plain("\n".join(lines))


def list_record(listing: FigureList) -> dict:
    """The list as JSON-ready data."""
    return {"figures": [{"number": f.number, "title": f.title, "has_simulation": f.has_simulation,
                         "sides": list(f.sides), "starts": [s.name for s in starts_of(f.number)],
                         "claims": [{"id": c.id, "source": c.source, "verdict": c.verdict} for c in f.claims]}
                        for f in listing.figures],
            "results_file": listing.results_file, "note": listing.note}


# --- one figure --------------------------------------------------------------------------------

@dataclass(frozen=True)
class PaperFigure:
    """A figure made again: its claims' records (as the report's, from :func:`claim_record
    <verify.report.claim_records.claim_record>`), the drawn images and the comparison with results.json.

    ``images`` are :class:`verify.report.figures.Image` (file name, PNG bytes, alt text);
    ``stored`` maps a claim id to results.json's verdict (empty without the file); ``mismatches``
    lists (claim id, computed verdict, stored verdict) where they differ.
    """

    number: int
    title: str
    side: Optional[str]
    has_simulation: bool
    records: tuple
    images: tuple
    stored: dict = field(default_factory=dict)
    mismatches: tuple = ()
    results_file: Optional[str] = None
    note: str = ""


def check_figure_number(n) -> int:
    """``n`` as a figure number 1..20 (an int or a decimal integer string); ValueError otherwise."""
    text = str(n).strip()
    if isinstance(n, bool) or not re.fullmatch(r"[0-9]+", text) or not 1 <= int(text) <= N_FIGURES:
        raise ValueError(f"figure {n!r}: allowed an integer 1 to {N_FIGURES}")
    return int(text)


def check_side(n: int, side: Optional[str]) -> Optional[str]:
    """``side`` for figure ``n``: None for the whole figure (None or ``"both"``), else a panel the figure has."""
    if side is None or side == "both":
        return None
    if side not in SIDE_CHOICES:
        raise ValueError(f"side {side!r}: allowed {', '.join(SIDE_CHOICES)}")
    sides = tuple(s for s in ("lhs", "rhs") if s in panel_sides(n) or any(side_of(c.source) == s for c in _claims_of(n)))
    if side not in sides:
        allowed = ", ".join(sides + ("both",))
        raise ValueError(f"side {side!r}: Fig. {n} has no {side.upper()} panel; allowed: {allowed}")
    return side


def _claims_of(n: int) -> tuple:
    return tuple(c for c in all_claims() if figure_of(c.source) == n)


def _panel(fig_data, side: Optional[str]):
    """The FigureData of one panel (its runs with that side, named ``fig-05-lhs``), or all of it."""
    if side is None:
        return fig_data
    return replace(fig_data, name=f"{fig_data.name}-{side}", title=f"{fig_data.title} ({side.upper()})",
                   runs=tuple(r for r in fig_data.runs if r.side == side))


def make_figure(n, side: Optional[str] = None, results_path: Optional[Path] = None) -> PaperFigure:
    """Evaluate the claims of paper figure ``n`` and draw its runs, as the report does.

    Parameters
    ----------
    n : int or str
        The figure number, 1 to 20.
    side : {None, "both", "lhs", "rhs"}
        ``"lhs"``/``"rhs"``: only that panel's claims (and the claims on the whole figure) and
        runs (controls and extra runs, which carry no side, are drawn only for the whole figure).
    results_path : Path, optional
        The report's results.json (default :data:`RESULTS_FILE`), whose verdicts are compared
        with the computed ones.

    Returns
    -------
    PaperFigure
        The records, the images (none for a figure without a run: Figs. 1, 7, 8, 13, 14) and
        the comparison.  Every claim of the figure is evaluated (the figure data hang on the
        first panel's evaluation); only the chosen side's are returned.
    """
    from .report.claim_records import claim_record  # lazy: not for 'figure --list'
    from .report.figures import render  # lazy: matplotlib (1 s) only to draw; not for 'figure --list'

    n = check_figure_number(n)
    side = check_side(n, side)
    results_path = Path(RESULTS_FILE if results_path is None else results_path)
    stored = {k: r["verdict"] for k, r in (read_results(results_path) or {}).items()}
    records, images, mismatches = [], [], []
    for claim in _claims_of(n):
        ev = claim.evaluate()
        for fig_data in ev.figures:
            panel = _panel(fig_data, side)
            if panel.runs:
                images.append(render(panel))
        if side is not None and side_of(claim.source) not in (side, None):
            continue
        records.append(claim_record(claim, ev))
        if claim.id in stored and stored[claim.id] != ev.verdict:
            mismatches.append((claim.id, ev.verdict, stored[claim.id]))
    names = [img.filename for img in images]
    if len(set(names)) != len(names):
        raise RuntimeError(f"Fig. {n}: two figures of its claims share a file name: {names}")
    has_run = n in figures_with_runs()
    if not stored:
        note = f"no {results_path}: verdicts not compared; run {HOW_TO_REPORT}"
    else:
        note = f"verdicts compared with {results_path}"
    if not has_run:
        note += f"; Fig. {n} has no run to draw (no simulation: its claims are decided without one)"
    return PaperFigure(n, figure_titles()[n], side, has_run, tuple(records), tuple(images),
                       {r["id"]: stored.get(r["id"]) for r in records}, tuple(mismatches),
                       str(results_path) if stored else None, note)


def figure_text(fig: PaperFigure) -> str:
    """The caption's words and the suite's verdict on each, with its correction or qualification."""
    panel = f"  [the {fig.side.upper()} panel only]" if fig.side else ""
    lines = [f"Fig. {fig.number}: {fig.title}{panel}", ""]
    for rec in fig.records:
        stored = fig.stored.get(rec["id"])
        agree = "" if stored in (None, rec["verdict"]) else f"  (results.json: {stored})"
        lines.append(f"{rec['source']} [{rec['id']}]: {rec['verdict'].upper()}{agree}")
        lines += [f'  "{" ".join(q.split())}"' for q in rec["quote"]]
        for key, label in (("reading", "read as"), ("expected", "the suite finds"), ("correction", "correction"),
                           ("qualification", "qualification")):
            if rec.get(key):
                lines.append(f"  {label}: {' '.join(str(rec[key]).split())}")
        if rec["verdict"] == NOT_CHECKABLE and rec.get("detail"):
            lines.append(f"  why: {' '.join(rec['detail'].split())}")
        lines.append("")
    if not fig.records:
        lines += ["(no claims)", ""]
    lines.append(fig.note)
    return plain("\n".join(lines))


def next_step(fig: PaperFigure) -> str:
    """One line: the commands to look further (an animation, a start's run), or the list."""
    if not fig.has_simulation:
        runs = ", ".join(str(n) for n in figures_with_runs())
        return f"next: python -m verify figure --list (the figures with runs: {runs})"
    starts = starts_of(fig.number, fig.side)
    side = fig.side or "both"
    return (f"next: python -m verify animate --figure {fig.number} --side {side} --out fig{fig.number}.gif; "
            f"python -m verify trajectory --start {starts[0].name} --output run.csv")

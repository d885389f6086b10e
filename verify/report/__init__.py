"""The report room: the claims' and the studies' data in, REPORT.md, report.html, results.json,
the conservation table and the figures out (:func:`write_report`, the one writer of each)."""
from .write import write_report

__all__ = ["write_report"]

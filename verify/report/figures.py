"""Figures: run data in, PNG bytes out (matplotlib, Agg, no timestamps in the file).

:func:`render` draws a caption's runs; :func:`png_bytes` is the one place a figure becomes bytes
(:mod:`.study_figures` draws the studies' figures with it)."""
from __future__ import annotations

import io
from dataclasses import dataclass

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ..claims.base import FigureData  # noqa: E402

@dataclass(frozen=True)
class Image:
    """A drawn figure: its file name (with extension), bytes and alt text."""

    filename: str
    data: bytes
    alt: str


ROWS = (("path", "y / R"), ("theta", "theta"), ("phi", "phi"), ("omega3", "omega3"))


def render(fig_data: FigureData) -> bytes:
    """One column per run: the centre-of-mass path, theta(t), phi(t), omega3(t)."""
    n = len(fig_data.runs)
    fig, axes = plt.subplots(4, n, figsize=(4.2 * n, 9.5), squeeze=False)
    for j, run in enumerate(fig_data.runs):
        ax = axes[0][j]
        ax.plot(run.x, run.y, lw=0.8)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x / R")
        ax.set_title(f"{run.label}\n{run.outcome}, max|E - E(0)|/|E(0)| = {run.energy_drift:.1e}", fontsize=8)
        for i, (name, label) in enumerate(ROWS[1:], start=1):
            a = axes[i][j]
            a.plot(run.t, getattr(run, name), lw=0.8)
            a.set_xlabel("t / s")
            a.set_ylabel(label)
        axes[0][j].set_ylabel(fig_data.path_label + ": " + ROWS[0][1])
    fig.suptitle(fig_data.title, fontsize=10)
    fig.tight_layout()
    return png_bytes(fig)


def png_bytes(fig) -> bytes:
    """The figure as PNG bytes (72 dpi, no software or date metadata: reproducible), then closed."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=72, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()

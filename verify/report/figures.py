"""Figures: run data in, :class:`Image` out (PNG bytes and alt text; matplotlib, Agg, no metadata).

:func:`render` draws a caption's runs (:func:`draw` returns the matplotlib Figure before it
becomes bytes, for tests); the style, the column width and the PNG encoder are
:mod:`.style`'s, shared with :mod:`.study_figures` and :mod:`.retrograde`.

Units: the models measure time in s with g/L = 980 s^-2 (models/common.py: g = 980 cm s^-2 and
the length unit L = 1 cm), lengths in L -- the disk's or ring's radius R, the hurricane balls'
ball radius a -- angles in rad and rates in rad/s.
"""
from __future__ import annotations

import textwrap
from dataclasses import dataclass

import matplotlib
import numpy as np

from ..claims.base import FigureData
from .. import style
from ..style import plt, png_bytes

#: the time series of a caption's figure: (RunData attribute, axis label, unit)
SERIES = (("theta", r"$\theta$ / rad", "rad"), ("phi", r"$\phi$ / rad", "rad"),
          ("omega3", r"$\omega_3$ / (rad/s)", "rad/s"))
#: a series whose range is below this fraction of its magnitude is drawn as a constant (its range stated)
FLAT = 1e-6


@dataclass(frozen=True)
class Image:
    """A figure of the report: its file name under ``figures/``, the PNG bytes and the alt text
    (one or two sentences on what it shows, from its data)."""

    filename: str
    data: bytes
    alt: str


def length_unit(fig_data: FigureData) -> tuple:
    """(symbol, meaning) of the length unit of the figure's path: the hurricane balls' lengths are
    in units of the ball radius a (models/hurricane.py), every other body's in its radius R.
    Read from the caption's title, which names the hurricane balls."""
    if "hurricane" in fig_data.title.lower():
        return "a", "the ball radius a"
    return "R", "the radius R"


def draw(fig_data: FigureData):
    """The matplotlib Figure of :func:`render` (call inside ``matplotlib.rc_context(style.RC)``).

    One column per run: the path (x, y in the length unit), theta(t), phi(t), omega3(t); a
    single run is drawn in a 2 x 2 grid instead."""
    runs = fig_data.runs
    n = len(runs)
    unit, _ = length_unit(fig_data)
    if n == 1:
        fig = plt.figure(figsize=(style.COLUMN_WIDTH, 6.4))
        grid = fig.add_gridspec(2, 2)
        columns = [[fig.add_subplot(grid[i // 2, i % 2]) for i in range(4)]]
        wrap = 100
    else:
        fig = plt.figure(figsize=(style.COLUMN_WIDTH, 9.2))
        grid = fig.add_gridspec(4, n, height_ratios=(1.5, 1, 1, 1))
        columns = [[fig.add_subplot(grid[i, j]) for i in range(4)] for j in range(n)]
        wrap = int(100 / n)
    for run, axes in zip(runs, columns):
        ax = axes[0]
        ax.plot(run.x, run.y, color=style.RUN)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel(f"x / {unit}")
        ax.set_ylabel(f"{fig_data.path_label}: y / {unit}")
        ax.set_title(textwrap.fill(run.label, wrap) + f"\n{run.outcome}, max|E - E(0)|/|E(0)| = {run.energy_drift:.1e}")
        t = np.asarray(run.t, float)
        for a, (name, label, u) in zip(axes[1:], SERIES):
            _series(a, t, np.asarray(getattr(run, name), float), u)
            a.set_xlabel("t / s")
            a.set_ylabel(label)
    fig.suptitle(fig_data.title)
    return fig


def _series(ax, t, v, unit: str) -> None:
    """v(t); a series constant to FLAT of its magnitude is drawn on a readable scale around its
    value with its range written in the panel (instead of an offset axis such as 1e-12+1.3)."""
    ax.plot(t, v, color=style.RUN)
    span, size = float(np.ptp(v)), float(np.max(np.abs(v)))
    if span <= FLAT * size or size == 0.0:
        mid = float(np.mean(v))
        pad = 0.05 * abs(mid) if mid else 1.0
        ax.set_ylim(mid - pad, mid + pad)
        ax.text(0.02, 0.92, f"constant: range {span:.1e} {unit}", transform=ax.transAxes, va="top",
                fontsize=style.MIN_FONT_PT, bbox=dict(facecolor="white", edgecolor="0.7", pad=2))


def alt_text(fig_data: FigureData) -> str:
    """What :func:`render` shows, from the data: the runs, their outcome and ranges."""
    unit, meaning = length_unit(fig_data)
    t = np.concatenate([np.asarray(r.t, float) for r in fig_data.runs])
    runs = "; ".join(
        f"{r.label}: {r.outcome}, theta {_range(r.theta)} rad, omega3 {_range(r.omega3)} rad/s"
        for r in fig_data.runs)
    n = len(fig_data.runs)
    return (f"{fig_data.title}: for {n} run{'s' if n > 1 else ''}, the {fig_data.path_label} path in the plane "
            f"(in units of {meaning}) and theta, phi, omega3 against time from {t.min():g} to {t.max():g} s. "
            f"{runs}.")


def _range(values) -> str:
    v = np.asarray(values, float)
    lo, hi = float(v.min()), float(v.max())
    return f"{lo:.4g}" if f"{lo:.4g}" == f"{hi:.4g}" else f"{lo:.4g} to {hi:.4g}"


def render(fig_data: FigureData) -> Image:
    """The caption's figure ``<name>.png``: one column per run, see :func:`draw`."""
    with matplotlib.rc_context(style.RC):
        data = png_bytes(draw(fig_data), style.LINE_PALETTE)
    return Image(f"{fig_data.name}.png", data, alt_text(fig_data))


def with_alt_text(markdown_text: str, alts: dict) -> str:
    """``markdown_text`` with each image line ``![...](<dir>/<name>)`` of a figure in ``alts``
    (file name -> alt text, results.json's ``figures``) given that figure's alt text."""
    lines = []
    for line in markdown_text.split("\n"):
        if line.startswith("![") and line.endswith(")") and "](" in line:
            target = line.split("](", 1)[1][:-1]
            alt = alts.get(target.rsplit("/", 1)[-1])
            if alt is not None:
                alt = alt.replace("[", "(").replace("]", ")").replace("\n", " ")
                line = f"![{alt}]({target})"
        lines.append(line)
    return "\n".join(lines)

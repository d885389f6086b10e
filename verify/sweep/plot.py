"""Maps of a sweep, drawn from its store: a quantity over two axes, one panel per value of a third.

``[plot]`` in the spec names ``x``, ``y`` (axes), the ``quantity`` (default: the first
recorded one), ``log`` (colour on a log scale) and optionally ``panels`` (an axis: one map per
value).  Axes not drawn are averaged over (the title says so).  Points a run did not reach
(NaN) are left white.
"""
from __future__ import annotations

import io
import math

import numpy as np

from .spec import ALWAYS, SweepSpec


def grid_of(spec: SweepSpec, rows: list, quantity: str, x: str, y: str, panel_value=None, panels: str = None):
    """(x values, y values, Z (len(y), len(x))) of ``quantity``, averaged over the other axes."""
    xs = next(a.values for a in spec.axes if a.name == x)
    ys = next(a.values for a in spec.axes if a.name == y)
    total = np.zeros((len(ys), len(xs)))
    count = np.zeros((len(ys), len(xs)))
    xi = {v: i for i, v in enumerate(xs)}
    yi = {v: i for i, v in enumerate(ys)}
    for r in rows:
        if panels is not None and r[f"in_{panels}"] != panel_value:
            continue
        v = r.get(quantity)
        if v is None or (isinstance(v, float) and math.isnan(v)):
            continue
        i, j = yi[r[f"in_{y}"]], xi[r[f"in_{x}"]]
        total[i, j] += v
        count[i, j] += 1
    with np.errstate(invalid="ignore"):
        return np.array(xs), np.array(ys), np.where(count > 0, total / np.maximum(count, 1), np.nan)


def render(spec: SweepSpec, rows: list, title: str = None) -> bytes:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm

    plot = spec.plot
    names = [a.name for a in spec.axes]
    x = plot.get("x", names[0])
    y = plot.get("y", names[1] if len(names) > 1 else names[0])
    quantity = plot.get("quantity", spec.record[0] if spec.record else ALWAYS[0])
    panels = plot.get("panels")
    values = next(a.values for a in spec.axes if a.name == panels) if panels else (None,)
    averaged = [n for n in names if n not in {x, y, panels}]
    fig, axs = plt.subplots(1, len(values), figsize=(4.2 * len(values) + 1, 4), squeeze=False)
    for ax, pv in zip(axs[0], values):
        X, Y, Z = grid_of(spec, rows, quantity, x, y, pv, panels)
        norm = None
        if plot.get("log"):
            positive = Z[np.isfinite(Z) & (Z > 0)]
            if positive.size:
                norm = LogNorm(vmin=positive.min(), vmax=positive.max())
        mesh = ax.pcolormesh(X, Y, np.ma.masked_invalid(Z), shading="nearest", norm=norm, cmap="viridis")
        fig.colorbar(mesh, ax=ax, label=quantity)
        for name, axis_set in ((x, ax.set_xscale), (y, ax.set_yscale)):
            if next(a.scale for a in spec.axes if a.name == name) == "log":
                axis_set("log")
        ax.set_xlabel(x)
        ax.set_ylabel(y)
        if panels:
            ax.set_title(f"{panels} = {pv:.4g}", fontsize=9)
    head = title or plot.get("title") or f"{spec.name}: {quantity}"
    if averaged:
        head += f" (mean over {', '.join(averaged)})"
    fig.suptitle(head, fontsize=10)
    buf = io.BytesIO()
    fig.tight_layout()
    fig.savefig(buf, format="png", dpi=100, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()

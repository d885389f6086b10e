"""Maps of a sweep, drawn from its store: a quantity over two axes, one panel per value of a third.

``[plot]`` in the spec names ``x``, ``y`` (axes), the ``quantity`` (default: the first
recorded one), ``log`` (colour on a log scale) and optionally ``panels`` (an axis: one map per
value).  Axes not drawn are averaged over (the title says so).  Points a run did not reach
(NaN) are left white.

A yes/no quantity (:data:`verify.sweep.spec.YES_NO`: ``slipped``, the retrograde turn, ...) and
``outcome`` (how each run ended) are categories, not numbers: they are drawn one run a cell in
the report's yes/no colours (:mod:`verify.style`), with a legend that names each category
and counts its runs (:func:`categories`), never on a colour bar nor averaged over an axis.
"""
from __future__ import annotations

import io
import math

import numpy as np

from .spec import ALWAYS, OUTCOME, YES_NO, SweepSpec


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


def _category_colours() -> tuple:
    """The cells' colours in category order: yes, no, then the others (verify.style's roles)."""
    from .. import style  # lazy: matplotlib (0.3 s) only when a map is drawn; grid_of needs numpy alone

    return (style.YES, style.NO, style.UNDECIDED, style.TOO_SHORT, style.RUN, style.PREDICTED, style.EDGE)


def _label(spec: SweepSpec, quantity: str, row: dict) -> str:
    """The category of one run: yes/no (or why neither) for a yes/no quantity, how it ended for ``outcome``."""
    outcome = row["outcome"]
    failed = outcome.startswith("failed:")
    if quantity != OUTCOME:
        v = row.get(quantity)
        if failed:
            return f"{outcome} (no value)"
        if v is None or (isinstance(v, float) and math.isnan(v)):
            return "not read (NaN)"
        return "yes" if v > 0.5 else "no"
    if failed:
        return outcome
    if spec.slips:
        return {"slips": "slipped", "ok": "did not slip by t_end", "contact_lost": "lost contact first"}.get(
            outcome, f"{outcome} first (no slip before)")
    return "reached t_end" if outcome == "ok" else f"stopped by {outcome}"


def categories(spec: SweepSpec, rows: list, quantity: str) -> tuple:
    """The categories of ``quantity`` over ``rows``, in drawing order: yes (slipped) first, no (did not
    slip, reached t_end) second, then the others in the order their runs come.  Yes and no (and with
    a coefficient and ``outcome``, the three a slip map always names: slipped, did not, lost contact
    first) are listed even where no run falls in them: an empty category is a result too.
    """
    first = ["yes", "no"] if quantity != OUTCOME else (
        ["slipped", "did not slip by t_end", "lost contact first"] if spec.slips
        else ["reached t_end"])
    seen = dict.fromkeys(_label(spec, quantity, r) for r in rows)
    return tuple(first + [c for c in seen if c not in first])


def render(spec: SweepSpec, rows: list, title: str = None) -> bytes:
    quantity = spec.plot.get("quantity", spec.record[0] if spec.record else ALWAYS[0])
    if quantity in YES_NO or quantity == OUTCOME:
        return render_categories(spec, rows, quantity, title)
    import matplotlib  # lazy: only when a map is drawn (as style above)

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: as matplotlib
    from matplotlib.colors import LogNorm  # lazy: as matplotlib

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
        _dress(ax, spec, x, y, panels, pv)
    head = title or plot.get("title") or f"{spec.name}: {quantity}"
    if averaged:
        head += f" (mean over {', '.join(averaged)})"
    fig.suptitle(head, fontsize=10)
    buf = io.BytesIO()
    fig.tight_layout()
    fig.savefig(buf, format="png", dpi=100, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


def render_categories(spec: SweepSpec, rows: list, quantity: str, title: str = None) -> bytes:
    """A categorical map (module docstring): one cell per run, a colour per category, counts in the legend."""
    import matplotlib  # lazy: only when a map is drawn (as style above)

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: as matplotlib
    from matplotlib.colors import BoundaryNorm, ListedColormap  # lazy: as matplotlib
    from matplotlib.patches import Patch  # lazy: as matplotlib

    plot = spec.plot
    names = [a.name for a in spec.axes]
    x = plot.get("x", names[0])
    y = plot.get("y", names[1] if len(names) > 1 else names[0])
    panels = plot.get("panels")
    values = next(a.values for a in spec.axes if a.name == panels) if panels else (None,)
    cats = categories(spec, rows, quantity)
    palette = _category_colours()
    if len(cats) > len(palette):
        raise ValueError(f"{spec.name}: {len(cats)} categories of {quantity!r} to draw, at most {len(palette)}")
    code = {c: i for i, c in enumerate(cats)}
    cmap = ListedColormap(palette[: len(cats)])
    norm = BoundaryNorm(np.arange(-0.5, len(cats)), cmap.N)
    xs = np.array(next(a.values for a in spec.axes if a.name == x))
    ys = np.array(next(a.values for a in spec.axes if a.name == y))
    xi, yi = {v: i for i, v in enumerate(xs)}, {v: i for i, v in enumerate(ys)}
    counts = dict.fromkeys(cats, 0)
    fig, axs = plt.subplots(1, len(values), figsize=(4.6 * len(values) + 1.4, 5.4), squeeze=False, layout="constrained")
    for ax, pv in zip(axs[0], values):
        Z = np.full((len(ys), len(xs)), np.nan)  # a point with no run stored stays white
        for r in rows:
            if panels is not None and r[f"in_{panels}"] != pv:
                continue
            label = _label(spec, quantity, r)
            counts[label] += 1
            Z[yi[r[f"in_{y}"]], xi[r[f"in_{x}"]]] = code[label]
        ax.pcolormesh(xs, ys, np.ma.masked_invalid(Z), shading="nearest", cmap=cmap, norm=norm)
        _dress(ax, spec, x, y, panels, pv)
    handles = [Patch(facecolor=palette[code[c]], edgecolor="0.5", label=f"{c} ({counts[c]})") for c in cats]
    fig.legend(handles=handles, loc="outside lower center", ncols=2 if len(values) > 1 else 1, fontsize=9,
               title=f"{quantity}: runs per category")
    fig.suptitle(title or plot.get("title") or f"{spec.name}: {quantity}", fontsize=10)
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()


def _dress(ax, spec, x: str, y: str, panels, value) -> None:
    """Axis scales (log where the spec's axis is), labels, and the panel's title."""
    for name, axis_set in ((x, ax.set_xscale), (y, ax.set_yscale)):
        if next(a.scale for a in spec.axes if a.name == name) == "log":
            axis_set("log")
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    if panels:
        ax.set_title(f"{panels} = {value:.4g}", fontsize=9)

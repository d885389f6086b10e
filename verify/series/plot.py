"""The picture of one run: the panels the paper's captions describe, with units on every axis.

:func:`draw_run` lays out six panels from a run's columns (:class:`~.columns.RunColumns`, from a
live run or a file read back by :func:`~.files.read_run`):

1. the centre of mass's path in the plane and the contact point's trace (P = C + r_P, paper Eqs.
   7, 47, 63, drawn by the animation's geometry), in the body's length unit;
2. theta(t), 3. phi(t), 4. omega3(t) = phidot cos(theta) + psidot (paper Eq. 16);
5. E(t) - E(0), or E + W - E(0) for a Coulomb run (W the work of friction), in the energy unit:
   the conservation check at a glance (for a dissipative model, E - E(0) is the energy lost);
6. N/(M g) (contact holds while it is positive) and, for a Coulomb run, the slip speed.

:func:`plot_bytes` renders PNG, SVG or PDF with the report's style (:mod:`verify.style`) and no
time stamps in the file, so the same run gives the same bytes.
"""
from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from .columns import RunColumns
from .files import output_path

FORMATS = (".png", ".svg", ".pdf")
#: the files' metadata left out (dates), so that a file is the same bytes on every run
_METADATA = {".png": {"Software": None}, ".svg": {"Date": None}, ".pdf": {"CreationDate": None, "Producer": None}}


def contact_trace(model: str, params: dict, theta, phi, x, y):
    """(x, y) of the contact point P = C + r_P on the plane (paper Eqs. 7, 47, 63), or None without
    a contact (the gyroscope's pivot, the effective model): :mod:`verify.animation.geometry`'s."""
    from ..animation import geometry  # lazy: verify.animation (17 ms) only to draw (not 'trajectory' alone)

    kind = geometry.DRAWN_MODELS.get(model)
    if kind not in ("disk", "ring", "hurricane") or (kind == "ring" and "h" not in params):
        return None
    p = geometry.contact_point(kind, theta, phi, x, y, params)
    return p[:, 0], p[:, 1]


def draw_run(columns: RunColumns):
    """The matplotlib Figure of the six panels (call inside ``matplotlib.rc_context(style.RC)``)."""
    from ..style import plt  # lazy: matplotlib (0.7 s) only to draw (not 'trajectory' alone)

    m, u = columns.meta, columns.units
    f = columns.as_float
    t, theta, phi = f("t"), f("theta"), f("phi")
    x, y = f("x"), f("y")
    omega3 = f("phidot") * np.cos(theta) + f("psidot")
    length = u["x"]
    fig, axes = plt.subplots(2, 3, figsize=(12, 7))
    ax = axes[0, 0]
    ax.plot(x, y, label="centre of mass C")
    params = {k: float(v) for k, v in m.get("params", {}).items()}
    trace = contact_trace(m["model"], params, theta, phi, x, y)
    if trace is not None:
        ax.plot(trace[0], trace[1], lw=0.6, alpha=0.8, label="contact point P")
    ax.plot(x[:1], y[:1], "o", color="black", ms=4, label="start")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel(f"x / {length}")
    ax.set_ylabel(f"y / {length}")
    ax.set_title("path in the plane")
    ax.legend(loc="best")
    for a, values, label in ((axes[0, 1], theta, r"$\theta$ / rad"), (axes[0, 2], phi, r"$\phi$ / rad"),
                             (axes[1, 0], omega3, r"$\omega_3 = \dot\phi\cos\theta + \dot\psi$ / s$^{-1}$")):
        a.plot(t, values)
        a.set_xlabel("t / s")
        a.set_ylabel(label)
    _energy_panel(axes[1, 1], columns, t)
    _contact_panel(axes[1, 2], columns, t)
    fig.suptitle(_title(m))
    return fig


def _energy_panel(ax, columns: RunColumns, t) -> None:
    unit = columns.units.get("energy", "")
    if "energy_plus_work" in columns.values:
        e = columns.as_float("energy_plus_work")
        label, what = "E + W - E(0)", "energy balance (W: work of friction)"
    elif "energy" in columns.values:
        e = columns.as_float("energy")
        label = "E - E(0)"
        what = "energy lost to the couple" if "c" in columns.meta.get("params", {}) else "energy conservation"
    else:
        ax.set_visible(False)
        return
    ax.plot(t, e - e[0])
    ax.set_xlabel("t / s")
    ax.set_ylabel(f"{label} / ({unit})")
    ax.set_title(f"{what}: max |{label}| = {np.nanmax(np.abs(e - e[0])):.2e}")


def _contact_panel(ax, columns: RunColumns, t) -> None:
    if "slip_speed" in columns.values:
        ax.plot(t, columns.as_float("slip_speed"))
        ax.set_xlabel("t / s")
        ax.set_ylabel(f"slip speed / ({columns.units['slip_speed']})")
        ax.set_title("sliding where > 0")
    elif "normal_force" in columns.values:
        ax.plot(t, columns.as_float("normal_force"))
        ax.axhline(0.0, color="0.5", lw=0.6)
        ax.set_xlabel("t / s")
        ax.set_ylabel("N / (M g)")
        ax.set_title("normal force (contact while > 0)")
    else:
        ax.set_visible(False)


def _title(meta: dict) -> str:
    params = ", ".join(f"{k} = {_short(v)}" for k, v in meta.get("params", {}).items())
    return f"{meta['model']} ({params}), {meta.get('precision', '')}: {meta.get('outcome', '')}"


def _short(text) -> str:
    try:
        return f"{float(text):.6g}"
    except (TypeError, ValueError):
        return str(text)


def plot_bytes(columns: RunColumns, suffix: str) -> bytes:
    """The picture of the run as PNG, SVG or PDF bytes (``suffix`` one of :data:`FORMATS`)."""
    import matplotlib  # lazy: matplotlib (0.3 s) only to draw (not 'trajectory' alone)

    from .. import style  # lazy: matplotlib (0.6 s) only to draw (not 'trajectory' alone)

    suffix = suffix.lower()
    if suffix not in FORMATS:
        raise ValueError(f"unknown picture format {suffix!r}; allowed {', '.join(FORMATS)}")
    with matplotlib.rc_context(style.RC):
        fig = draw_run(columns)
        buffer = io.BytesIO()
        fig.savefig(buffer, format=suffix[1:], metadata=_METADATA[suffix])
        style.plt.close(fig)
    return buffer.getvalue()


def picture_path(text: str, option: str = "--plot") -> Path:
    """The checked picture file (:func:`verify.series.files.output_path`'s rule, the picture formats)."""
    return output_path(text, option, FORMATS)


def write_plot(columns: RunColumns, path) -> Path:
    """Draw the run into ``path`` (PNG, SVG or PDF by its extension), atomically."""
    from ..provenance import write_atomic  # lazy: verify.provenance (30 ms) only to draw (not 'trajectory' alone)

    path = Path(path)
    write_atomic(path, plot_bytes(columns, path.suffix))
    return path

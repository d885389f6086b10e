"""The report's figure style: one set of rcParams, the column width, the colours and the PNG encoder.

Every figure of the report is drawn inside ``matplotlib.rc_context(RC)`` (:func:`figure`) and
becomes bytes in :func:`png_bytes`.  Sizes are chosen for the displayed size: a figure is
:data:`COLUMN_WIDTH` inches wide at :data:`DPI`, i.e. 900 px, the width of the report's column,
so 1 pt of font is 100/72 px on the page (a 9 pt tick label is 12.5 px, the size of 9.4 pt text
at the browser's 96 px per inch).
"""
from __future__ import annotations

import io
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from PIL import Image as PILImage  # noqa: E402

DPI = 100
#: inches: 900 px at DPI, the width of the report's text column
COLUMN_WIDTH = 9.0
#: the smallest font of any figure, in pt at the displayed size
MIN_FONT_PT = 9

#: one colour per role, the same in every figure
RUN = "#1f77b4"  # a run's curve
PREDICTED = "#d62728"  # a prediction drawn over it (a slope, a linear threshold)
CONTOUR = "white"  # a level drawn on a colour map (growth factor)
EDGE = "black"  # the edge of a region (runs that left)
SHADE = "0.9"  # a window (the fit window)
#: the colours of a yes/no map and of the cells that have no yes/no to show
YES, NO = "#e66101", "#5e3c99"
UNDECIDED, TOO_SHORT = "0.78", "0.93"
COLOUR_MAP = "viridis"

RC = {
    "figure.dpi": DPI,
    "savefig.dpi": DPI,
    "figure.facecolor": "white",
    "savefig.facecolor": "white",
    "figure.constrained_layout.use": True,
    "font.size": 10,
    "axes.titlesize": 10,
    "axes.labelsize": 10,
    "xtick.labelsize": MIN_FONT_PT,
    "ytick.labelsize": MIN_FONT_PT,
    "legend.fontsize": MIN_FONT_PT,
    "legend.title_fontsize": MIN_FONT_PT,
    "figure.titlesize": 11,
    # the offset ("1e-12+1.3" above an axis) hides the values; near-constant series are drawn
    # by the figures with a stated range instead (figures._flat)
    "axes.formatter.useoffset": False,
    "axes.formatter.use_mathtext": True,
    "axes.grid": True,
    "grid.color": "0.88",
    "grid.linewidth": 0.6,
    "axes.prop_cycle": matplotlib.cycler(color=[RUN, "#ff7f0e", "#2ca02c", PREDICTED, "#9467bd"]),
    "lines.linewidth": 1.0,
    "image.cmap": COLOUR_MAP,
    "svg.hashsalt": "verify-report",
}


def figure(width_fraction: float = 1.0, height: float = 5.0, **subplots):
    """``plt.subplots`` at ``width_fraction`` of the column width and ``height`` inches, in the style.

    Must be called inside ``matplotlib.rc_context(RC)`` (the figure takes its style when drawn
    too); returns (figure, axes) as ``plt.subplots``."""
    return plt.subplots(figsize=(COLUMN_WIDTH * width_fraction, height), **subplots)


def _ramps(colours, levels: int) -> bytes:
    """A PNG palette: ``levels`` steps from white to each of ``colours`` (endpoints exact)."""
    out = [(255, 255, 255)]
    for c in colours:
        end = np.array(matplotlib.colors.to_rgb(c)) * 255
        out += [tuple(int(v) for v in np.round(255 + (end - 255) * k / (levels - 1))) for k in range(1, levels)]
    return bytes(v for rgb in dict.fromkeys(out) for v in rgb)


#: the palette of the line figures (:data:`RUN` and :data:`PREDICTED` curves, black text, grey grid and
#: shading): 6 antialiasing steps from the white background to each of them
LINE_COLOURS = ("black", RUN, PREDICTED, "0.88", SHADE, "0.4")
LINE_PALETTE = _ramps(LINE_COLOURS, 6)


def png_bytes(fig, palette: bytes = None) -> bytes:
    """The figure as an optimised palette PNG (no metadata: reproducible bytes), then closed.

    The figure is rasterised at :data:`DPI` on white.  With ``palette`` (e.g. :data:`LINE_PALETTE`)
    each pixel takes the nearest of its colours: the curves, text and grid keep their exact
    colours and only the antialiased edges lose gradation (6 steps instead of ~100), which
    halves the bytes of the dense time series.  Without, a figure of at most 256 distinct
    colours keeps them all and one with more (a continuous colour map) is reduced to 256 by
    median cut; no dithering either way (deterministic).
    """
    fig.canvas.draw()
    rgb = np.asarray(fig.canvas.buffer_rgba())[..., :3]
    plt.close(fig)
    packed = (rgb[..., 0].astype(np.uint32) << 16) | (rgb[..., 1].astype(np.uint32) << 8) | rgb[..., 2]
    colours, index = np.unique(packed.ravel(), return_inverse=True)
    channels = np.stack([colours >> 16, (colours >> 8) & 255, colours & 255], -1).astype(float)
    if palette is not None:  # nearest palette colour (Euclidean in RGB) of each distinct colour
        table = np.frombuffer(palette, np.uint8).reshape(-1, 3).astype(float)
        nearest = np.argmin(((channels[:, None, :] - table[None, :, :]) ** 2).sum(-1), axis=1)
        img = PILImage.fromarray(nearest[index].reshape(packed.shape).astype(np.uint8), "P")
        img.putpalette(palette)
    elif len(colours) <= 256:  # exact: every colour kept
        img = PILImage.fromarray(index.reshape(packed.shape).astype(np.uint8), "P")
        img.putpalette(channels.astype(np.uint8).tobytes())
    else:
        img = PILImage.fromarray(np.ascontiguousarray(rgb), "RGB").quantize(
            colors=256, method=PILImage.Quantize.MEDIANCUT, dither=PILImage.Dither.NONE)
    buf = io.BytesIO()
    img.save(buf, format="png", optimize=True)
    return buf.getvalue()


#: the units an axis label may end in (" / <unit>", also inside a closing parenthesis such as
#: log10(tilt / rad)): time, angle, rate, and the lengths in units of the body's radius R or the
#: hurricane balls' ball radius a; a dimensionless ratio says "(ratio)"
UNITS = ("s", "rad", "(rad/s)", "R", "a")
_UNIT = re.compile(r" / (" + "|".join(re.escape(u) for u in UNITS) + r")\)?$")


def has_unit(label: str) -> bool:
    """Whether an axis label names its unit (mathtext ``$`` ignored)."""
    plain = label.replace("$", "").strip()
    return bool(_UNIT.search(plain)) or plain.endswith("(ratio)")


def labels_without_units(fig) -> list:
    """The axis labels of ``fig`` that name no unit (:func:`has_unit`), empty ones included: both
    axes of every panel that shows data, the long axis of every colour bar."""
    missing = []
    for ax in fig.axes:
        if hasattr(ax, "_colorbar"):
            labels = [ax.get_ylabel() or ax.get_xlabel()]
        elif ax.has_data():
            labels = [ax.get_xlabel(), ax.get_ylabel()]
        else:
            continue
        missing += [label for label in labels if not has_unit(label)]
    return missing


def small_texts(fig) -> list:
    """The visible texts of ``fig`` set smaller than :data:`MIN_FONT_PT` (tick labels included)."""
    fig.canvas.draw()
    return [(t.get_text(), t.get_fontsize()) for t in fig.findobj(matplotlib.text.Text)
            if t.get_visible() and t.get_text() and t.get_fontsize() < MIN_FONT_PT]

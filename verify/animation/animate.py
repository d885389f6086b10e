"""Animate one or more runs side by side, sharing one clock, to a GIF, MP4 or HTML file.

>>> from verify.animation import AnimationRun, animate
>>> record = animate([run_stable, run_unstable], "fig5_spins.gif")    # doctest: +SKIP
>>> record.frames, record.speed                                       # doctest: +SKIP

The clock (speed rule, frame times, interpolation) is :mod:`verify.animation.timing`; a
panel's drawing and camera :mod:`verify.animation.scene`; the body geometry
:mod:`verify.animation.geometry` and :mod:`verify.animation.shapes`.
"""
from __future__ import annotations

import hashlib
import os
import re
import shutil
import tempfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .errors import AnimationError
from .revolution import profile_for
from .run import AnimationRun, checked_arrays
from . import geometry, timing

#: Output formats by extension, and what writes them.
FORMATS = {".gif": "Pillow (through matplotlib)", ".mp4": "ffmpeg on PATH", ".html": "matplotlib's to_jshtml, offline"}
DPI = 100
#: Height of the image over one panel's width.
PANEL_ASPECT = 0.9


@dataclass(frozen=True)
class AnimationRecord:
    """What :func:`animate` wrote: the file, frames rendered, frames per second, speed (sim s per
    animation s), whether the speed was raised to fit ``max_seconds``, the rule that set it,
    and the image size in pixels (width, height)."""

    file: Path
    frames: int
    fps: float
    speed: float
    raised: bool
    rule: str
    size: tuple


def _check_output(out) -> tuple:
    path = Path(out)
    ext = path.suffix.lower()
    if ext not in FORMATS:
        raise AnimationError(f"output {str(out)!r} has extension {path.suffix or 'none'!r}; allowed: "
                             + ", ".join(FORMATS))
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise AnimationError(f"output folder {str(folder)!r} does not exist; allowed: an existing folder")
    if ext == ".mp4" and shutil.which("ffmpeg") is None:
        raise AnimationError("writing .mp4 needs ffmpeg on PATH, which is not there: install it "
                             "(apt-get install ffmpeg) or write .gif or .html")
    return path, ext


def _check_number(name: str, value, lower: float) -> float:
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise AnimationError(f"{name}={value!r}; allowed: a number > {lower:g}") from None
    if not np.isfinite(number) or number <= lower:
        raise AnimationError(f"{name}={value!r}; allowed: a finite number > {lower:g}")
    return number


def _time_text(t: float, step: float) -> str:
    decimals = int(max(2, np.ceil(-np.log10(step)) if step > 0 else 2))
    return f"{t:.{decimals}f}"


def build(runs, *, speed=None, fps=25, width_px=480, max_seconds=20.0):
    """The figure, panels and clock of an animation, not yet written (for :func:`animate` and tests).

    Returns
    -------
    (matplotlib.figure.Figure, list of Panel, Clock, callable)
        The last item draws frame k and returns the changed artists.
    """
    from matplotlib.figure import Figure  # lazy: matplotlib (0.5 s) only to draw; 'animate' checks --out first

    from .scene import Panel  # lazy: .scene imports matplotlib (0.5 s), as Figure above

    runs = list(runs) if not isinstance(runs, AnimationRun) else [runs]
    if not runs or not all(isinstance(r, AnimationRun) for r in runs):
        raise AnimationError(f"runs={runs!r:.80}; allowed: one AnimationRun or a non-empty list of them")
    fps = _check_number("fps", fps, 0)
    max_seconds = _check_number("max_seconds", max_seconds, 0)
    if speed is not None:
        speed = _check_number("speed", speed, 0)
    width = int(_check_number("width_px", width_px, 15)) // 2 * 2  # even: video encoders need it
    params = [geometry.checked_params(r.model, r.params) for r in runs]
    profiles = [profile_for(r.model, r.body, p) if geometry.body_kind(r.model) == "revolution" else None
                for r, p in zip(runs, params)]
    arrays = [checked_arrays(r) for r in runs]
    for run, a in zip(runs, arrays):
        timing.check_grid(run.label, a)
    clock = timing.clock(arrays, fps, speed, max_seconds)
    n = len(runs)
    height = int(round(width / n * PANEL_ASPECT)) // 2 * 2
    fig = Figure(figsize=(width / DPI, height / DPI), dpi=DPI)
    fig.subplots_adjust(left=0, right=1, bottom=0, top=0.9, wspace=0)
    fontsize = max(4.0, min(11.0, width / n / 40))
    panels = [Panel(fig.add_subplot(1, n, i + 1, projection="3d"), run.label, run.model, p, a, clock.times, fontsize,
                    profile)
              for i, (run, p, a, profile) in enumerate(zip(runs, params, arrays, profiles))]
    common = max(p.span for p in panels)
    for p in panels:  # one scale for every panel
        p.widen(common)
    text = fig.text(0.5, 0.985, "", ha="center", va="top", fontsize=fontsize, family="monospace")
    step = clock.speed / fps
    state = timing.speed_text(clock.speed) + (f", to fit {clock.times[-1] / clock.speed:.3g} s" if clock.raised else "")

    def draw(k: int) -> list:
        text.set_text(f"t = {_time_text(clock.times[k], step)} s, {state}")
        return [a for p in panels for a in p.update(k)] + [text]

    draw(0)
    return fig, panels, clock, draw


def animate(runs, out, *, speed=None, fps=25, width_px=480, max_seconds=20.0) -> AnimationRecord:
    """Animate ``runs`` side by side (one panel each, one shared clock) into the file ``out``.

    Parameters
    ----------
    runs : AnimationRun or sequence of AnimationRun
        The runs; panels from left to right in this order.
    out : str or os.PathLike
        The file to write, by its extension: ``.gif`` (Pillow), ``.mp4`` (ffmpeg on PATH) or
        ``.html`` (self-contained: the frames embedded as PNG by matplotlib's ``to_jshtml``,
        no network needed).  Written to a temporary file in the same folder and moved into
        place (``os.replace``): nothing half-written on an error or Ctrl-C.
    speed : float, optional
        Simulated seconds per second of animation.  Default: the fastest turning of the
        bodies is shown at one turn per second, never faster than real time, raised to fit
        ``max_seconds`` (rule in :mod:`verify.animation.timing`).
    fps : float
        Frames per second (GIF stores frame durations in whole 1/100 s: 25 or 50 are exact).
    width_px : int
        Width of the whole image in pixels (rounded down to even); each panel is
        ``width_px / len(runs)`` wide and the image ``0.9`` panel widths high (even).
    max_seconds : float
        The longest animation: the default speed is raised to fit it; a given ``speed``
        that does not fit is refused.

    Returns
    -------
    AnimationRecord

    Raises
    ------
    AnimationError
        A bad run, option or output path, or ``.mp4`` without ffmpeg (one line naming the
        value and what is allowed); nothing is written then.

    Notes
    -----
    Same input, same bytes for GIF and HTML (the HTML's random element id is replaced by one
    from a hash of the frames).  Pillow merges identical consecutive GIF frames into one of
    their summed duration, so a GIF of a still body can hold fewer frames than rendered.
    """
    path, ext = _check_output(out)
    fig, panels, clock, draw = build(runs, speed=speed, fps=fps, width_px=width_px, max_seconds=max_seconds)
    from matplotlib import animation, rc_context  # lazy: matplotlib (0.5 s), as in build()
    from matplotlib.backends.backend_agg import FigureCanvasAgg  # lazy: as the line above

    FigureCanvasAgg(fig)
    n = len(clock.times)
    anim = animation.FuncAnimation(fig, draw, frames=n, interval=1000.0 / fps, blit=False, repeat=False)
    fd, temp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=ext, dir=path.parent if str(path.parent) else ".")
    os.close(fd)
    try:
        if ext == ".gif":
            anim.save(temp, writer=animation.PillowWriter(fps=fps), dpi=DPI)
        elif ext == ".mp4":
            writer = animation.FFMpegWriter(fps=fps, codec="libx264", bitrate=-1,
                                            extra_args=["-pix_fmt", "yuv420p", "-map_metadata", "-1",
                                                        "-fflags", "+bitexact", "-flags:v", "+bitexact"])
            anim.save(temp, writer=writer, dpi=DPI)
        else:
            with rc_context({"animation.embed_limit": 1e4}):  # MB; the default 20 drops frames silently
                html = anim.to_jshtml(fps=fps, default_mode="once")
            Path(temp).write_text(_offline_html(html), encoding="utf-8")
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(temp, 0o666 & ~umask)  # mkstemp made it 0600: give it an ordinary file's mode
        os.replace(temp, path)
    except BaseException:
        Path(temp).unlink(missing_ok=True)
        raise
    width, height = fig.canvas.get_width_height()
    return AnimationRecord(path, n, float(fps), clock.speed, clock.raised, clock.rule, (width, height))


#: matplotlib's jshtml draws its buttons with Font Awesome from a CDN; offline they are these characters.
BUTTON_TEXT = {"fa-fast-backward": "&#x23EE;", "fa-step-backward": "&#x23F4;|", "fa-play fa-flip-horizontal": "&#x25C0;",
               "fa-pause": "&#x23F8;", "fa-play": "&#x25B6;", "fa-step-forward": "|&#x23F5;",
               "fa-fast-forward": "&#x23ED;", "fa-minus": "&#x2212;", "fa-plus": "+"}


def _offline_html(html: str) -> str:
    """The jshtml page made offline and reproducible: the stylesheet link to the icon CDN removed
    and the icons written as characters; matplotlib's random element id (uuid4) replaced by a
    hash of the page.  A remote reference left (a newer matplotlib) raises AnimationError."""
    html = re.sub(r"<link[^>]*font-awesome[^>]*>", "", html)
    for icon, text in BUTTON_TEXT.items():
        html = html.replace(f'<i class="fa {icon}"></i>', text)
    remote = re.search(r"""(?:src|href)\s*=\s*["']?(?:https?:)?//[^"'\s>]+""", html)
    if remote:
        raise AnimationError(f"matplotlib's HTML page loads {remote.group(0)!r}; allowed: an offline page "
                             "(write .gif instead)")
    ids = set(re.findall(r"_anim_img([0-9a-f]{32})", html))
    for old in ids:
        new = hashlib.sha256(html.replace(old, "").encode()).hexdigest()[:32]
        html = html.replace(old, new)
    return html

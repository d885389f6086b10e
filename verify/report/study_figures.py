"""The studies' figures: a stability map and the dissipative spin-down, drawn from the studies' data.

:func:`render_map` draws a :class:`verify.studies.maps.StabilityMap`, :func:`render_dissipation`
the :class:`verify.studies.dissipation.LawStudy` records; neither runs anything.  Each returns a
:class:`.figures.Image`; :func:`draw_map` and :func:`draw_dissipation` return the matplotlib
Figure before it becomes bytes (call them inside ``matplotlib.rc_context(style.RC)``).
"""
from __future__ import annotations

import math
import textwrap

import matplotlib
import numpy as np
from matplotlib.lines import Line2D

from models.ring import parameter_set_name
from models.steady import RATE_NAMES

from ..studies.dissipation import LawStudy, secants
from ..studies.maps import GROWTH, StabilityMap
from .. import style
from .figures import Image
from ..style import png_bytes


def render_map(smap: StabilityMap) -> Image:
    """The map ``map-<model>-<motion>.png`` (see :func:`draw_map`) with its alt text."""
    with matplotlib.rc_context(style.RC):
        data = png_bytes(draw_map(smap))
    return Image(f"map-{smap.model}-{smap.motion}.png", data, map_alt_text(smap))


def map_alt_text(smap: StabilityMap) -> str:
    """What the map shows, from its data: grid, share of runs that grow or leave, the threshold."""
    rate_name = RATE_NAMES.get(smap.motion, "rate")
    grows = int(np.count_nonzero(smap.growth >= GROWTH))
    threshold = ("no linear threshold" if smap.linear_threshold is None
                 else f"the linear threshold at {rate_name} = {smap.linear_threshold:.6g} rad/s")
    return (f"Stability map of the {smap.model}'s {smap.motion}: growth of a theta perturbation in "
            f"{smap.t_end:g} s over spin rate {rate_name} from {smap.rates.min():g} to {smap.rates.max():g} rad/s "
            f"and initial tilt from {smap.tilts.min():.1e} to {smap.tilts.max():.1e} rad. "
            f"{grows} of {smap.growth.size} runs grow by {GROWTH} or more ({int(np.count_nonzero(smap.left))} left the "
            f"steady motion); {threshold}.")


def draw_map(smap: StabilityMap):
    """The map: x = rate, y = log10(tilt), colour = log10(max deviation / tilt).

    The linear threshold is a vertical red line whose legend label gives its value; the
    contour where the growth factor reaches GROWTH (the classification of
    :func:`verify.studies.thresholds.grows`) is white, the edge of the runs that left is dashed black.
    The title names model, motion and parameters.

    Parameters
    ----------
    smap : verify.studies.maps.StabilityMap

    Returns
    -------
    matplotlib.figure.Figure
    """
    ly = np.log10(smap.tilts)
    colour = np.log10(np.maximum(smap.growth, np.finfo(float).tiny))
    fig, ax = style.figure(height=5.4)
    ax.grid(False)
    mesh = ax.pcolormesh(smap.rates, ly, colour, shading="nearest", cmap=style.COLOUR_MAP)
    bar = fig.colorbar(mesh, ax=ax)
    bar.set_label(r"$\log_{10}$ growth: max $|\theta - \theta_\mathrm{steady}|$ / initial tilt (ratio)")
    handles = []
    if smap.linear_threshold is not None:
        handles.append(ax.axvline(smap.linear_threshold, color=style.PREDICTED, lw=1.5,
                                  label=f"linear threshold {smap.linear_threshold:.6g} rad/s"))
    if len(smap.rates) > 1 and len(smap.tilts) > 1:
        order = np.argsort(smap.rates)
        rows = np.argsort(ly)
        x, y = smap.rates[order], ly[rows]
        if colour.min() < math.log10(GROWTH) < colour.max():
            ax.contour(x, y, colour[np.ix_(rows, order)], levels=[math.log10(GROWTH)], colors=style.CONTOUR, linewidths=1.2)
            handles.append(Line2D([], [], color=style.CONTOUR, lw=1.2, label=f"growth = {GROWTH}"))
        if smap.left.any() and not smap.left.all():
            ax.contour(x, y, smap.left[np.ix_(rows, order)].astype(float), levels=[0.5], colors=style.EDGE,
                       linewidths=1.2, linestyles="dashed")
            handles.append(Line2D([], [], color=style.EDGE, lw=1.2, ls="dashed",
                                  label=f"left (|dev| = {smap.cap:g} rad, domain end or contact)"))
    if handles:
        ax.legend(handles=handles, loc="upper right", facecolor="0.85")
    rate_name = RATE_NAMES.get(smap.motion, "rate")
    ax.set_xlabel(f"spin rate {rate_name} / (rad/s)")
    ax.set_ylabel(r"$\log_{10}$(initial tilt / rad)")
    shown = ", ".join(f"{k} = {float(v):g}" for k, v in smap.params.items())
    if smap.model.startswith("ring"):  # name the ring's parameter set (models.ring: annular defaults or printed)
        shown = f"{parameter_set_name(smap.params) or 'other'} set: {shown}"
    ax.set_title(textwrap.fill(f"{smap.model}, {smap.motion} ({shown}): growth of a theta perturbation in "
                               f"{smap.t_end:g} s", 110))
    return fig


def render_dissipation(results) -> Image:
    """``dissipation.png`` (see :func:`draw_dissipation`) with its alt text."""
    results = tuple(results)
    with matplotlib.rc_context(style.RC):
        data = png_bytes(draw_dissipation(results), style.LINE_PALETTE)
    laws = "; ".join(f"{s.law}: p = {s.fit.p:.5f} (predicted {s.fit.p_predicted}), q = {s.fit.q:.5f} "
                     f"(predicted {s.fit.q_predicted}), run {s.run.outcome}" for s in results)
    alt = ("Dissipative spin-down of the disk: theta and the secant phidot against the time to the "
           f"singularity t0 - t, log-log, for {len(results)} laws with the predicted slopes. {laws}.")
    return Image("dissipation.png", data, alt)


def draw_dissipation(results):
    """theta and phidot (secant) against t0 - t, log-log, one column per law, with the predicted
    slopes p and q drawn through the middle of the fit window (shaded)."""
    results = tuple(results)
    fig, axes = style.figure(height=7.6, nrows=2, ncols=len(results), squeeze=False)
    for j, s in enumerate(results):
        _panels(axes[0][j], axes[1][j], s, wrap=int(95 / len(results)))
    fig.suptitle("Dissipative spin-down of the disk towards theta = 0 (fit window shaded)")
    return fig


def _panels(ax_theta, ax_phidot, s: LawStudy, wrap: int):
    fit, run = s.fit, s.run
    t, th = np.asarray(run.t, float), np.asarray(run["theta"], float)
    mid, _, phd = secants(run)
    tmid = np.interp(-np.log(mid), -np.log(th), t)  # the time each secant's mid-angle is passed
    lo, hi = fit.window
    series = ((ax_theta, fit.t0 - t, th, th, fit.p_predicted, r"$\theta$ / rad"),
              (ax_phidot, fit.t0 - tmid, phd, mid, fit.q_predicted, r"$\dot\phi$ (secant) / (rad/s)"))
    for ax, tau, y, angle, slope, label in series:
        keep = (tau > 0) & (y > 0)
        ax.loglog(tau[keep], y[keep], ".", ms=3, color=style.RUN, label=f"run, c = {float(s.prediction.c):g} ({run.outcome})")
        centre = np.nonzero(keep & (angle >= lo) & (angle <= hi))[0]
        if len(centre):
            i = centre[len(centre) // 2]
            xs = np.geomspace(tau[keep].min(), tau[keep].max(), 50)
            ax.loglog(xs, y[i] * (xs / tau[i]) ** float(slope), "-", lw=1.0, color=style.PREDICTED,
                      label=f"slope {slope} (predicted)")
        band = fit.t0 - np.interp(-np.log([hi, lo]), -np.log(th), t)
        ax.axvspan(band.min(), band.max(), color=style.SHADE, zorder=0)
        at = fit.t0 - np.interp(-math.log(fit.breakdown_theta), -np.log(th), t) if math.isfinite(fit.breakdown_theta) else 0
        if at > 0:
            ax.axvline(at, color="0.4", ls=":", lw=0.8, label=f"breakdown, theta = {fit.breakdown_theta:.2g}")
        ax.set_xlabel(r"$t_0 - t$ / s")
        ax.set_ylabel(label)
        ax.legend()
    ax_theta.set_title(textwrap.fill(f"{s.law} (n = {s.family.exponent}): p = {fit.p:.5f} (predicted "
                                     f"{fit.p_predicted}), q = {fit.q:.5f} ({fit.q_predicted})", wrap))

"""The studies' figures: a stability map and the dissipative spin-down, drawn from the studies' data.

:func:`render_map` draws a :class:`verify.studies.maps.StabilityMap`, :func:`render_dissipation`
the :class:`verify.studies.dissipation.LawStudy` records; neither runs anything.
"""
from __future__ import annotations

import math

import numpy as np
from matplotlib.lines import Line2D

from models.ring import parameter_set_name
from models.steady import RATE_NAMES

from ..studies.dissipation import LawStudy, secants
from ..studies.maps import GROWTH, StabilityMap
from .figures import plt, png_bytes


def render_map(smap: StabilityMap) -> bytes:
    """PNG of the map: x = rate, y = log10(tilt), colour = log10(max deviation / tilt).

    The linear threshold is a vertical red line whose legend label gives its value; the
    contour where the growth factor reaches GROWTH (the classification of
    :func:`verify.studies.thresholds.grows`) is white, the edge of the runs that left is dashed black.
    The title names model, motion and parameters.

    Parameters
    ----------
    smap : verify.studies.maps.StabilityMap

    Returns
    -------
    bytes
        The PNG (matplotlib Agg, 72 dpi, no software or date metadata: reproducible bytes).
    """
    ly = np.log10(smap.tilts)
    colour = np.log10(np.maximum(smap.growth, np.finfo(float).tiny))
    fig, ax = plt.subplots(figsize=(7.5, 5.0))
    mesh = ax.pcolormesh(smap.rates, ly, colour, shading="nearest", cmap="viridis")
    bar = fig.colorbar(mesh, ax=ax)
    bar.set_label("log10(max |theta - theta_steady| / tilt)")
    handles = []
    if smap.linear_threshold is not None:
        handles.append(ax.axvline(smap.linear_threshold, color="red", lw=1.2,
                                  label=f"linear threshold {smap.linear_threshold:.6g}"))
    if len(smap.rates) > 1 and len(smap.tilts) > 1:
        order = np.argsort(smap.rates)
        rows = np.argsort(ly)
        x, y = smap.rates[order], ly[rows]
        if colour.min() < math.log10(GROWTH) < colour.max():
            ax.contour(x, y, colour[np.ix_(rows, order)], levels=[math.log10(GROWTH)], colors="white", linewidths=0.9)
            handles.append(Line2D([], [], color="white", lw=0.9, label=f"growth = {GROWTH}"))
        if smap.left.any() and not smap.left.all():
            ax.contour(x, y, smap.left[np.ix_(rows, order)].astype(float), levels=[0.5], colors="black",
                       linewidths=0.9, linestyles="dashed")
            handles.append(Line2D([], [], color="black", lw=0.9, ls="dashed",
                                  label=f"left (|dev| = {smap.cap:g} rad, domain end or contact)"))
    if handles:
        ax.legend(handles=handles, loc="upper right", fontsize=7, facecolor="0.85")
    rate_name = RATE_NAMES.get(smap.motion, "rate")
    ax.set_xlabel(f"spin rate {rate_name} (rad/s)")
    ax.set_ylabel("log10(initial tilt / rad)")
    shown = ", ".join(f"{k} = {float(v):g}" for k, v in smap.params.items())
    if smap.model.startswith("ring"):  # name the ring's parameter set (models.ring: annular defaults or printed)
        shown = f"{parameter_set_name(smap.params) or 'other'} set: {shown}"
    ax.set_title(f"{smap.model}, {smap.motion} ({shown}): growth of a theta perturbation in {smap.t_end:g} s",
                 fontsize=9)
    fig.tight_layout()
    return png_bytes(fig)


def render_dissipation(results) -> bytes:
    """PNG of theta and phidot (secant) against t0 - t, log-log, one column per law, with the
    predicted slopes p and q drawn through the middle of the fit window (shaded)."""
    results = tuple(results)
    fig, axes = plt.subplots(2, len(results), figsize=(5.2 * len(results), 7.5), squeeze=False)
    for j, s in enumerate(results):
        _panels(axes[0][j], axes[1][j], s)
    fig.suptitle("Dissipative spin-down of the disk towards theta = 0 (fit window shaded)", fontsize=10)
    fig.tight_layout()
    return png_bytes(fig)


def _panels(ax_theta, ax_phidot, s: LawStudy):
    fit, run = s.fit, s.run
    t, th = np.asarray(run.t, float), np.asarray(run["theta"], float)
    mid, _, phd = secants(run)
    tmid = np.interp(-np.log(mid), -np.log(th), t)  # the time each secant's mid-angle is passed
    lo, hi = fit.window
    series = ((ax_theta, fit.t0 - t, th, th, fit.p_predicted, "theta"),
              (ax_phidot, fit.t0 - tmid, phd, mid, fit.q_predicted, "phidot / s^-1 (secant)"))
    for ax, tau, y, angle, slope, label in series:
        keep = (tau > 0) & (y > 0)
        ax.loglog(tau[keep], y[keep], ".", ms=3, label=f"run, c = {float(s.prediction.c):g} ({run.outcome})")
        centre = np.nonzero(keep & (angle >= lo) & (angle <= hi))[0]
        if len(centre):
            i = centre[len(centre) // 2]
            xs = np.geomspace(tau[keep].min(), tau[keep].max(), 50)
            ax.loglog(xs, y[i] * (xs / tau[i]) ** float(slope), "-", lw=0.8, label=f"slope {slope} (predicted)")
        band = fit.t0 - np.interp(-np.log([hi, lo]), -np.log(th), t)
        ax.axvspan(band.min(), band.max(), color="0.9", zorder=0)
        at = fit.t0 - np.interp(-math.log(fit.breakdown_theta), -np.log(th), t) if math.isfinite(fit.breakdown_theta) else 0
        if at > 0:
            ax.axvline(at, color="0.4", ls=":", lw=0.8, label=f"breakdown, theta = {fit.breakdown_theta:.2g}")
        ax.set_xlabel("t0 - t / s")
        ax.set_ylabel(label)
        ax.legend(fontsize=7)
    ax_theta.set_title(f"{s.law} (n = {s.family.exponent}): p = {fit.p:.5f} (predicted {fit.p_predicted}), "
                       f"q = {fit.q:.5f} ({fit.q_predicted})", fontsize=8)

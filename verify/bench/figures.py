"""The benchmarks' two figures from their results: work against precision, and the energy error against time."""
from __future__ import annotations

import io
import math

import numpy as np


def render_work_precision(r: dict) -> bytes:
    import matplotlib  # lazy: matplotlib (0.3 s) only when a figure is drawn, not for the numbers

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: as matplotlib above

    wp = r["work_precision"]
    fig, ax = plt.subplots(figsize=(7.5, 5))
    floor = wp["reference_floor"]
    methods = []
    for a in wp["attempts"]:
        if a["method"] not in methods:
            methods.append(a["method"])
    for mname in methods:
        pts = [a for a in wp["attempts"] if a["method"] == mname and math.isfinite(a["error"])]
        if not pts:
            continue
        pts.sort(key=lambda a: a["seconds"])
        ax.loglog([a["seconds"] for a in pts], [max(a["error"], floor) for a in pts], "o-", label=mname)
    ax.axhline(floor, color="grey", ls=":", lw=1, label="reference's agreed accuracy")
    ax.set_xlabel("wall time (s)")
    ax.set_ylabel("final-state error (relative, max norm)")
    ax.set_title(f"work against precision: {wp['case']}, t = {wp['t_end']} s")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    return _png(fig)


def render_energy(r: dict) -> bytes:
    import matplotlib  # lazy: matplotlib (0.3 s) only when a figure is drawn, not for the numbers

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt  # lazy: as matplotlib above

    e = r["energy"]
    t = np.array(e["times"])
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for key, text in (("suite", "verify.solve"), ("suite_high_accuracy", "verify.solve, high accuracy"),
                      ("plain", "plain heyoka")):
        ax.loglog(t, e["rms"][key], label=f"{text}: t^{e['exponent'][key]:.2f}")
    guide = e["rms"]["suite_high_accuracy"][-1] * np.sqrt(t / t[-1])
    ax.loglog(t, guide, "k:", lw=1, label="t^0.5 (Brouwer)")
    ax.set_xlabel("t (s)")
    ax.set_ylabel("relative energy error (RMS over starts)")
    ax.set_title(f"disk, about {e['steps_per_run']:,} steps per run")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    return _png(fig)


def _png(fig) -> bytes:
    import matplotlib.pyplot as plt  # lazy: as matplotlib above

    buf = io.BytesIO()
    fig.tight_layout()
    fig.savefig(buf, format="png", dpi=100, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()

"""The report's tippe-top section: the study's data (a job of ``make report``) and its Markdown.

:func:`job_data` is what :func:`verify.report.jobs.tippe_top_job` returns (results.json's
``studies.tippe_top``); :func:`render_markdown` turns it into the section, every number read from it.
"""
from __future__ import annotations

from . import runs


def job_data() -> dict:
    """The whole study (:func:`runs.study`): thresholds, groups, smooth and Coulomb runs, predictions."""
    return runs.study(quick=False)


def _t(x) -> str:
    return "—" if x is None else f"{x:.3g}"


def render_markdown(data: dict) -> str:
    """The section ``## Tippe top`` from :func:`job_data`'s record."""
    th = data["thresholds"]["tippe-top"]
    grp = data["groups"]
    lines = ["## Tippe top", "",
             "A sphere whose centre of mass sits α = 0.3 below its centre (I1/I3 = "
             f"{grp['tippe-top']['ratio']:g}), started at θ0 = {runs.START_TILT} with spin n about its axis and its "
             f"centre at rest, μ = {runs.FRICTION}, under the smooth law F_h = −μN u/√(|u|² + ε²) and under exact "
             "Coulomb friction ([docs/tippe-top.md](../docs/tippe-top.md)). From Jellett's integral and the energy: "
             f"the inverted spin is within the energy's reach above n_E = {th['energy_bound']:.6f} s⁻¹ and is a "
             f"minimum of V_λ (so the top inverts) above n_s = {th['inverted_minimum']:.6f} s⁻¹; the upright spin "
             f"is unstable above n_u = {th['upright_unstable']:.6f} s⁻¹. The stable body (I1/I3 = "
             f"{grp['tippe-top-stable']['ratio']:g}) and the hanging one ({grp['tippe-top-hanging']['ratio']:g}) lie "
             f"outside the window ({grp['tippe-top']['window'][0]:g}, {grp['tippe-top']['window'][1]:g}).", "",
             "| law | body | n (s⁻¹) | ε (R/s) | verdict | predicted | θ > 2.5 at (s) | z_C within 0.01 R of R + c at (s) "
             "| γ(L_C, e3) > 2.5 at (s) | end θ | end γ (steady) | E + W (ε) | Jellett (ε) |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in data["smooth"] + data["coulomb"]:
        p = data["predictions"][f"{r['body']}@{r['spin']:g}"]
        pred = p["verdict"] + (f" at {p['theta']:.4f}" if p["verdict"] == "tilted" else "")
        if r["law"] == "coulomb":
            slid = r["phases"][0][2] if r["phases"] and r["phases"][0][0] == "sliding" else 0.0
            verdict = f"slides {1e3 * slid:.1f} ms, sticks, rolls ({r['verdict']})"
            end = f"[{r['min_theta']:.3f}, {r['max_theta']:.3f}]"
            pred, eps = "—", "—"
        else:
            verdict, end, eps = r["verdict"], f"{r['end_theta']:.4f}", f"{r['eps']:g}"
        steady = "" if p.get("gamma") is None else f" ({p['gamma']:.4f})"
        lines.append(f"| {r['law']} | {r['body']} | {r['spin']:g} | {eps} | {verdict} | {pred} | {_t(r['t_theta'])} | "
                     f"{_t(r['t_height'])} | {_t(r['t_spin'])} | {end} | {r['end_gamma']:.4f}{steady} | "
                     f"{r['energy_plus_work_in_eps']:.3g} | {r['jellett_in_eps']:.3g} |")
    lines += ["", "Two measures of the inversion: the tilt θ of the axis, and γ, the angle between the angular "
              "momentum about C and the axis (from the rates: cos γ = I3 ω3/|L_C|); the verdict needs both, and says "
              "`disagree` when they do not agree. At a tilted end γ is the steady motion's (in brackets, from "
              "V_λ's minimum without integrating).",
              "", "Every smooth-law verdict is the energy–Jellett prediction; exact Coulomb friction sticks within "
              "25 ms and then rolls, keeping the energy, Jellett's and Routh's integrals, so it never turns over. "
              "The inversion time grows like 1/ε for small ε (the Coulomb limit) and like ε for large ε."]
    return "\n".join(lines)


__all__ = ["job_data", "render_markdown"]

"""Draw docs/figures/euler-angles.png: the 3-1-3 Euler angles of the suite, and theta for the
disk beside theta for the hurricane balls.

    python tools/euler_angles.py [--out docs/figures/euler-angles.png]

The vectors are those of models/symbols.py (paper Fig. 1):
e1 = (cos phi, sin phi, 0), e2 = (-sin phi cos theta, cos phi cos theta, sin theta),
e3 = (sin phi sin theta, -cos phi sin theta, cos theta); the disk's contact point is
r_P = -R e2, the hurricane balls' r_P = -a sin(theta) e2 - a (1 + cos(theta)) e3 (Eq. 63).
"""
from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

PHI, THETA, PSI = np.radians(35.0), np.radians(62.0), np.radians(55.0)
AZIM = 5.0
BLUE, RED, GREEN, GREY = "#1f5fa8", "#c0392b", "#1e8449", "#555555"


def frame(phi, theta):
    """e1, e2, e3 in inertial components (models/symbols.py)."""
    s, c, sp, cp = np.sin(theta), np.cos(theta), np.sin(phi), np.cos(phi)
    return (np.array([cp, sp, 0.0]), np.array([-sp * c, cp * c, s]), np.array([sp * s, -cp * s, c]))


def arc(centre, u, v, a0, a1, r, n=40):
    """Points r (cos a u + sin a v) about centre for a from a0 to a1."""
    a = np.linspace(a0, a1, n)
    return centre[:, None] + r * (np.outer(u, np.cos(a)) + np.outer(v, np.sin(a)))


def arrow3(ax, start, vec, colour, label, lw=2.0, offset=1.08, **kw):
    end = start + vec
    ax.plot(*np.c_[start, end], color=colour, lw=lw, **kw)
    ax.scatter(*end, color=colour, s=12)
    ax.text(*(start + offset * vec), label, color=colour, fontsize=12, ha="center", va="center")


def angle_arc(ax, pts, colour, label, at=0.55, shift=np.zeros(3)):
    ax.plot(*pts, color=colour, lw=1.6)
    k = int(at * (pts.shape[1] - 1))
    ax.text(*(pts[:, k] + shift), label, color=colour, fontsize=13, ha="center", va="center")


def disk_3d(ax):
    X, Y, Z = np.eye(3)
    e1, e2, e3 = frame(PHI, THETA)
    C = np.array([0.0, 0.0, np.sin(THETA)])          # the centre, R sin(theta) above the plane
    P = C - e2                                       # the contact point, r_P = -R e2
    # the plane z = 0
    g = np.linspace(-1.3, 1.3, 2)
    gx, gy = np.meshgrid(g, g)
    ax.plot_surface(gx, gy, np.zeros_like(gx), color="#dddddd", alpha=0.35, linewidth=0)
    # the disk: the circle C + R (cos a e1 + sin a e2)
    rim = arc(C, e1, e2, 0, 2 * np.pi, 1.0, 120)
    ax.plot(*rim, color="k", lw=1.2)
    ax.add_collection3d(matplotlib.collections.PolyCollection([rim[:2].T], alpha=0))  # keep limits
    ax.add_collection3d(Poly3DCollection([rim.T], facecolor="#f3d9a4", alpha=0.45, edgecolor="none"))
    # inertial axes through C (dashed) and the vertical
    for v, name in ((X, "X"), (Y, "Y"), (Z, "Z")):
        ax.plot(*np.c_[C, C + 1.25 * v], color=GREY, lw=1, ls="--")
        ax.text(*(C + 1.33 * v), name, color=GREY, fontsize=11)
    # the frame
    arrow3(ax, C, 1.2 * e1, BLUE, "e1 (line of nodes)", offset=1.25)
    arrow3(ax, C, 0.9 * e2, BLUE, "e2", offset=1.15)
    arrow3(ax, C, 1.2 * e3, BLUE, "e3 (axle)", offset=1.15)
    # a mark fixed in the body, at angle psi from e1 in the disk's plane
    b1 = np.cos(PSI) * e1 + np.sin(PSI) * e2
    ax.plot(*np.c_[C, C + b1], color=GREEN, lw=2.2)
    ax.scatter(*(C + b1), color=GREEN, s=25)
    ax.text(*(C + 1.12 * b1), "body mark", color=GREEN, fontsize=10)
    # the angles
    angle_arc(ax, arc(C, X, Y, 0, PHI, 0.55), RED, "φ", shift=np.array([0.12, -0.05, 0]))
    # theta: from Z to e3, turning about e1 (Z = cos a e3 + sin a e2 at a = theta)
    n_vec = np.cross(e1, Z)                      # e3 = cos(theta) Z + sin(theta) (e1 x Z)
    angle_arc(ax, arc(C, Z, n_vec, 0, THETA, 0.6), RED, "θ", shift=np.array([0, 0, 0.1]))
    angle_arc(ax, arc(C, e1, e2, 0, PSI, 0.45), GREEN, "ψ", shift=np.array([0, 0, 0.08]))
    ax.plot(*np.c_[P, C], color="k", lw=0.8, ls=":")
    ax.scatter(*P, color="k", s=18)
    ax.text(*(P + np.array([0, 0, -0.15])), "P", fontsize=11)
    ax.text(*(C + np.array([-0.12, 0.0, -0.12])), "C", fontsize=11)
    ax.set_xlim(-1.2, 1.2), ax.set_ylim(-1.2, 1.2), ax.set_zlim(-0.2, 2.2)
    ax.set_box_aspect((1, 1, 1))
    ax.view_init(elev=20, azim=AZIM)
    ax.set_axis_off()



def side_view(ax, theta, body):
    """The vertical plane through e3: horizontal unit u (e3's horizontal part), vertical Z."""
    e3 = np.array([np.sin(theta), np.cos(theta)])
    e2 = np.array([-np.cos(theta), np.sin(theta)])
    ax.axhline(0, color=GREY, lw=1)
    ax.fill_between([-2.5, 2.5], -0.25, 0, color="#dddddd")
    if body == "disk":
        C = np.array([np.cos(theta), np.sin(theta)])      # C = P + R e2, P at the origin
        ends = np.c_[C + e2, C - e2]                         # the disk seen edge on
        ax.plot(*ends, color="#b07d2b", lw=6, solid_capstyle="butt")
        ax.text(*(C + 0.15 * np.array([-1, 0]) - 0.9 * e2), "P", fontsize=10)
        label = "disk (R = 1): θ from Z to the axle e3\nθ = π/2 upright, θ → 0 lying flat"
        L = 1.0
    else:
        C = np.array([np.sin(theta), 1 + np.cos(theta)])    # the glue point, a (1 + cos θ) high
        for s in (-1, 1):
            ax.add_patch(plt.Circle(C + s * e3, 1.0, color="#9ab3d5", alpha=0.7, ec="k"))
        ax.plot(*(C - e3 + np.array([0, -1.0])), "ko", ms=3)
        ax.text(*(C - e3 + np.array([0.1, -0.95])), "P", fontsize=10)
        label = "hurricane balls (a = 1): θ from Z to the line\nof centres e3; θ = 0 upright, θ = π/2 both on the plane"
        L = 1.4
    ax.plot(*C, "ko", ms=3)
    ax.annotate("", xy=C + L * e3, xytext=C, arrowprops=dict(arrowstyle="->", color=BLUE, lw=2))
    ax.text(*(C + 1.1 * L * e3), "e3", color=BLUE, fontsize=11)
    ax.annotate("", xy=C + np.array([0, L]), xytext=C,
                arrowprops=dict(arrowstyle="->", color=GREY, lw=1.2, ls="--"))
    ax.text(*(C + np.array([-0.15, 1.05 * L])), "Z", color=GREY, fontsize=11)
    a = np.linspace(0, theta, 30)
    r = 0.55 * L
    ax.plot(C[0] + r * np.sin(a), C[1] + r * np.cos(a), color=RED, lw=1.6)
    ax.text(C[0] + 1.2 * r * np.sin(theta / 2), C[1] + 1.2 * r * np.cos(theta / 2), "θ",
            color=RED, fontsize=13, ha="center", va="center")
    ax.set_title(label, fontsize=10)
    ax.set_aspect("equal")
    ax.set_xlim(-1.6, 3.0), ax.set_ylim(-0.3, 4.0)
    ax.set_axis_off()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    out_default = Path(__file__).resolve().parent.parent / "docs" / "figures" / "euler-angles.png"
    parser.add_argument("--out", type=Path, default=out_default)
    args = parser.parse_args(argv)
    fig = plt.figure(figsize=(11, 6.6))
    fig.text(0.3, 0.96, "3-1-3 sequence: φ about Z, then θ about e1, then ψ about e3\n"
             "rotation R = Rz(φ) Rx(θ) Rz(ψ);  state order (θ, φ, ψ, θ̇, φ̇, ψ̇, x, y)",
             ha="center", va="top", fontsize=12)
    ax = fig.add_axes([0.0, 0.0, 0.6, 0.88], projection="3d")
    disk_3d(ax)
    side_view(fig.add_axes([0.6, 0.5, 0.38, 0.4]), np.radians(62.0), "disk")
    side_view(fig.add_axes([0.6, 0.0, 0.38, 0.42]), np.radians(35.0), "balls")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()

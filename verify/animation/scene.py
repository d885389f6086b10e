"""One panel of the animation: the body in perspective on a gridded floor (matplotlib mplot3d).

What a panel shows at each frame: the body (:mod:`verify.animation.shapes`, or a body file's
surface of revolution, :mod:`verify.animation.revolution`) shaded by the angle of each face to a
fixed light, its mark in red; on the floor the centre of mass's path so far (blue, C projected
onto the plane) and the contact point's trace (orange; the gyroscope has none: its pivot stands
on a post); the run's label above.  Below, a line with theta and, for a run with friction, what the
contact does (rolling, sliding) and its slip speed |u|, drawn as a dark arrow at the contact on
the floor (its length in body units is reach * |u| / max |u| of the run, said on the panel).
A tippe top's stem (drawn only) is said to be so on the panel.

Camera: fixed, framing the whole path (the bounding box of C and P over the run plus the
body's size), so the floor grid is still and the body's travel reads against it and the
path so far is visible in full.  A path longer than :data:`FOLLOW_SPAN` body sizes would make
the body too small: then the camera follows C with a window of that span (the grid then
moves under the body; the path is shown where it is inside the window).
"""
from __future__ import annotations

import numpy as np
from matplotlib.colors import to_rgb
from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

from . import geometry, revolution, shapes, timing

#: Path span (in body sizes) beyond which the camera follows the body.
FOLLOW_SPAN = 12.0
#: The body's horizontal reach from C (units of R or a) and its top height above the floor.
REACH = {"disk": 1.0, "ring": 1.0, "hurricane": 2.0, "gyroscope": 4.0}
BODY_COLOUR = {"disk": "#4a7fb5", "ring": "#c8a13a", "hurricane": "#7a8a99", "gyroscope": "#7a8a99",
               "revolution": "#4a7fb5"}
#: The length unit of each body's drawing (the hurricane balls' and gyroscope's: the ball radius a).
LENGTH_UNIT = {"hurricane": "a", "gyroscope": "a", "revolution": "L"}
UNIT_WORDS = {"R": "the body's radius R", "a": "the ball radius a", "L": "the body file's unit L"}
#: A stemmed sphere's half on the stem's side, and the stem (drawn only).
UPPER_COLOUR, STEM_COLOUR = "#e8b04a", "#3b3b3b"
MARK_COLOUR = "#d62728"
SLIP_COLOUR = "#222222"
PATH_COLOUR, TRACE_COLOUR = "#1f5fbf", "#ff8c1a"
#: Direction the light comes from (unit vector, inertial): above, from the camera's side.
LIGHT = np.array([-0.4, -0.6, 0.7]) / np.linalg.norm([-0.4, -0.6, 0.7])
ELEVATION, AZIMUTH = 28.0, -60.0


class Panel:
    """The artists of one run's panel and how to move them to frame k.

    Parameters
    ----------
    ax : mpl_toolkits.mplot3d.axes3d.Axes3D
        The panel's axes.
    label : str
        The run's label.
    model : str
        The run's model.
    params : dict
        Checked parameters (:func:`verify.animation.geometry.checked_params`).
    arrays : dict
        The run's checked arrays (grid).
    times : numpy.ndarray
        The frame times (simulated seconds).
    fontsize : float
        Label size in points.
    """

    def __init__(self, ax, label: str, model: str, params: dict, arrays: dict, times: np.ndarray, fontsize: float,
                 profile: revolution.Profile | None = None):
        self.ax = ax
        self.kind = kind = geometry.body_kind(model)
        self.profile = profile
        upper = None
        if kind == "revolution":
            self.mesh, upper = revolution.mesh(profile)
            self.reach = revolution.reach(profile)
        else:
            self.mesh = shapes.mesh_for(kind, params)
            self.reach = REACH[kind]
        self.params = params
        self.grid_t = arrays["t"]
        self.times = times
        s = timing.states_at(arrays, times)
        self.frame_theta = s["theta"]
        self.pivot_height = geometry.gyroscope_pivot_height(arrays["theta"]) if kind == "gyroscope" else 0.0
        self.rotations = geometry.rotation(s["theta"], s["phi"], s["psi"])
        self.centres = self._centre(s["theta"], s["x"], s["y"])
        self.path = np.stack([arrays["x"], arrays["y"]], -1)  # C on the floor, on the grid
        self.frame_path = np.stack([s["x"], s["y"]], -1)
        if kind == "gyroscope":
            pivot = geometry.pivot_point(arrays["theta"], arrays["phi"], arrays["x"], arrays["y"], self.pivot_height)
            self.trace, self.frame_trace = None, None
            marks = pivot[:, :2]
            self.pivot = pivot[0]
        else:
            self.trace = self.contact(arrays["theta"], arrays["phi"], arrays["x"], arrays["y"])[:, :2]
            self.frame_trace = self.contact(s["theta"], s["phi"], s["x"], s["y"])[:, :2]
            marks = self.trace
        self.slip, self.phase, self.slip_max = _frame_slip(arrays, times)
        base = np.array(to_rgb(BODY_COLOUR[kind]))
        self.base = base if upper is None else np.where(upper[:, None], np.array(to_rgb(UPPER_COLOUR)), base)
        self.mark = np.array(to_rgb(MARK_COLOUR))
        self.stem = kind == "revolution" and profile.stem
        self._frame_camera(np.concatenate([self.path, marks]))
        self._draw_static(label, fontsize)

    def _centre(self, theta, x, y) -> np.ndarray:
        if self.kind == "revolution":
            return np.stack([np.asarray(x, float), np.asarray(y, float), revolution.centre_height(self.profile, theta)], -1)
        return geometry.centre(self.kind, theta, x, y, self.params, self.pivot_height)

    def contact(self, theta, phi, x, y) -> np.ndarray:
        """The contact point P = C + r2 e2 + r3 e3 (the body's own contact vector)."""
        if self.kind != "revolution":
            return geometry.contact_point(self.kind, theta, phi, x, y, self.params)
        _, e2, e3 = geometry.frame(theta, phi)
        r2, r3 = revolution.contact_radii(self.profile, theta)
        return self._centre(theta, x, y) + r2[..., None] * e2 + r3[..., None] * e3

    def placed(self, k: int) -> tuple:
        """(quads, normals, colours) of the drawn body at frame k, the stem (cut at the floor) included."""
        rotation, centre = self.rotations[k], self.centres[k]
        quads, normals = self.mesh.placed(rotation, centre)
        colours = np.where(self.mesh.mark[:, None], self.mark, self.base)
        if self.stem:
            stem = revolution.stem_quads(self.profile, self.frame_theta[k], rotation, centre)
            quads = np.concatenate([quads, stem])
            normals = np.concatenate([normals, revolution.stem_normals(rotation)])
            colours = np.concatenate([colours, np.tile(to_rgb(STEM_COLOUR), (len(stem), 1))])
        return quads, normals, colours

    def _frame_camera(self, points: np.ndarray) -> None:
        reach = self.reach
        lo, hi = points.min(axis=0) - reach, points.max(axis=0) + reach
        span = float(max(np.max(hi - lo), 3 * reach))
        self.follow = span > FOLLOW_SPAN * reach
        if self.follow:
            span = FOLLOW_SPAN * reach
        self.span = span
        self.middle = (lo + hi) / 2
        self.top = max(float(self.centres[:, 2].max()) + reach, 0.5 * reach) if self.kind != "gyroscope" else \
            self.pivot_height + 4.0
        ax = self.ax
        ax.set_proj_type("persp", focal_length=0.6)
        ax.view_init(elev=ELEVATION, azim=AZIMUTH)
        ax.set_axis_off()
        ax.computed_zorder = False  # floor, then paths, then the body: the body is above the floor
        ax.set_box_aspect((1, 1, max(self.top / span, 0.05)), zoom=1.1)  # larger zooms clip the floor corner nearest the camera
        self._set_limits(self.middle)

    def widen(self, span: float) -> None:
        """Show a floor ``span`` wide (a fixed camera only, and only wider): panels side by side share one scale."""
        if self.follow or not span > self.span:
            return
        self.span = span
        self.ax.set_box_aspect((1, 1, max(self.top / span, 0.05)), zoom=1.1)
        self._set_limits(self.middle)
        self.floor.set_verts([self._floor_square(self.middle)])
        self.grid.set_segments(self._floor_segments(self.middle))

    def _floor_square(self, middle) -> list:
        half = self.span / 2
        return [(middle[0] - half, middle[1] - half, 0), (middle[0] + half, middle[1] - half, 0),
                (middle[0] + half, middle[1] + half, 0), (middle[0] - half, middle[1] + half, 0)]

    def _set_limits(self, middle) -> None:
        half = self.span / 2
        self.ax.set_xlim(middle[0] - half, middle[0] + half)
        self.ax.set_ylim(middle[1] - half, middle[1] + half)
        self.ax.set_zlim(0, self.top)

    def _floor_segments(self, middle) -> list:
        half = self.span / 2
        step = 10.0 ** np.floor(np.log10(self.span / 4))
        step *= 2 if self.span / step > 12 else 1
        segments = []
        for axis in (0, 1):
            for v in np.arange(np.ceil((middle[axis] - half) / step), np.floor((middle[axis] + half) / step) + 1) * step:
                a = [middle[1 - axis] - half, middle[1 - axis] + half]
                if axis == 0:
                    segments.append([(v, a[0], 0), (v, a[1], 0)])
                else:
                    segments.append([(a[0], v, 0), (a[1], v, 0)])
        return segments

    def _draw_static(self, label: str, fontsize: float) -> None:
        ax = self.ax
        m = self.middle
        self.floor = ax.add_collection3d(Poly3DCollection([self._floor_square(m)], facecolors="#eef0f2", edgecolors="none",
                                                          zorder=0))
        self.grid = ax.add_collection3d(Line3DCollection(self._floor_segments(m), colors="#c9ced6", linewidths=0.5, zorder=0.5))
        (self.path_line,) = ax.plot([], [], [], color=PATH_COLOUR, linewidth=1.0, label="C path", zorder=1)
        (self.trace_line,) = ax.plot([], [], [], color=TRACE_COLOUR, linewidth=1.0, label="contact trace", zorder=1)
        if self.kind == "gyroscope":
            p = self.pivot
            ax.plot([p[0], p[0]], [p[1], p[1]], [0, p[2]], color="#555555", linewidth=1.5, zorder=1.5)
        (self.slip_line,) = ax.plot([], [], [], color=SLIP_COLOUR, linewidth=1.6, zorder=1.8)
        self.body = ax.add_collection3d(Poly3DCollection(self.mesh.quads, linewidths=0.4, zorder=2))
        ax.set_title(label, fontsize=fontsize, pad=0)
        unit = LENGTH_UNIT.get(self.kind, "R")
        notes = [f"lengths in {UNIT_WORDS[unit]}, times in s"]
        if self.slip is not None:
            notes.append(f"arrow: the contact's slip u, {self.reach:.2g} {unit} long at max |u| = {self.slip_max:.3g} {unit}/s")
        if self.stem:
            notes.append("stem: drawn only (the model is the ball), cut at the floor")
        self.unit = unit
        small = 0.85 * fontsize
        self.status = ax.text2D(0.5, 0.99, "", transform=ax.transAxes, fontsize=small, family="monospace", ha="center",
                                va="top")
        ax.text2D(0.01, 0.0, "\n".join(notes), transform=ax.transAxes, fontsize=0.8 * small, va="bottom", color="#555555")

    def _inside(self, points: np.ndarray, k: int) -> np.ndarray:
        """``points`` with those off the floor's window set to NaN (mplot3d does not clip lines)."""
        if not self.follow:
            return points
        off = np.any(np.abs(points - self.centres[k, :2]) > self.span / 2, axis=1)
        return np.where(off[:, None], np.nan, points)

    def update(self, k: int) -> list:
        """Move the artists to frame k; returns them (for matplotlib's animation)."""
        t = self.times[k]
        quads, normals, colours = self.placed(k)
        light = 0.35 + 0.65 * np.abs(normals @ LIGHT)
        colours = np.clip(colours * light[:, None], 0, 1)
        self.body.set_verts(quads)
        self.body.set_facecolor(colours)
        self.body.set_edgecolor(colours)  # edges in the face's colour: no seams between faces
        n = int(np.searchsorted(self.grid_t, t, side="right"))
        path = self._inside(np.concatenate([self.path[:n], self.frame_path[k:k + 1]]), k)
        self.path_line.set_data_3d(path[:, 0], path[:, 1], np.zeros(len(path)))
        if self.trace is not None:
            trace = self._inside(np.concatenate([self.trace[:n], self.frame_trace[k:k + 1]]), k)
            self.trace_line.set_data_3d(trace[:, 0], trace[:, 1], np.zeros(len(trace)))
        status = f"\u03b8 = {self.frame_theta[k]:5.3f} rad"
        if self.slip is not None:
            u = self.slip[k]
            speed = float(np.hypot(*u))
            status += f", {self.phase[k]}, |u| = {speed:.3g} {self.unit}/s"
            arrow = _arrow(self.frame_trace[k], u * (self.reach / self.slip_max if self.slip_max > 0 else 0.0))
            self.slip_line.set_data_3d(arrow[:, 0], arrow[:, 1], np.zeros(len(arrow)))
        self.status.set_text(status)
        if self.follow:
            middle = self.centres[k, :2]
            self._set_limits(middle)
            self.floor.set_verts([self._floor_square(middle)])
            self.grid.set_segments(self._floor_segments(middle))
        return [self.body, self.path_line, self.trace_line, self.slip_line, self.status, self.floor, self.grid]


def _frame_slip(arrays: dict, times: np.ndarray) -> tuple:
    """(slip (n, 2), phase text (n,), max |u| on the grid) at the frame times, or (None, None, 0) without slip.

    The slip is interpolated linearly; the phase is the one of the last grid point at or before the frame."""
    if "slip_x" not in arrays:
        return None, None, 0.0
    t = arrays["t"]
    slip = np.stack([np.interp(times, t, arrays["slip_x"]), np.interp(times, t, arrays["slip_y"])], -1)
    index = np.clip(np.searchsorted(t, times, side="right") - 1, 0, len(t) - 1)
    phase = arrays["phase"][index] if "phase" in arrays else np.full(len(times), "slip")
    return slip, phase, float(np.max(np.hypot(arrays["slip_x"], arrays["slip_y"])))


def _arrow(start: np.ndarray, vector: np.ndarray) -> np.ndarray:
    """A polyline on the floor: the shaft from ``start`` along ``vector`` and a head of two barbs (NaN-separated)."""
    end = start + vector
    length = float(np.hypot(*vector))
    if length == 0:
        return np.full((1, 2), np.nan)
    back = -vector / length * min(0.35 * length, 0.25)
    side = np.array([-back[1], back[0]]) * 0.5
    return np.array([start, end, [np.nan, np.nan], end + back + side, end, end + back - side])

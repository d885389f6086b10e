"""One panel of the animation: the body in perspective on a gridded floor (matplotlib mplot3d).

What a panel shows at each frame: the body (:mod:`verify.animation.shapes`) shaded by the
angle of each face to a fixed light, its mark in red; on the floor the centre of mass's
path so far (blue, C projected onto the plane) and the contact point's trace (orange; the
gyroscope has none: its pivot stands on a post); the run's label above.

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

from . import geometry, shapes, timing

#: Path span (in body sizes) beyond which the camera follows the body.
FOLLOW_SPAN = 12.0
#: The body's horizontal reach from C (units of R or a) and its top height above the floor.
REACH = {"disk": 1.0, "ring": 1.0, "hurricane": 2.0, "gyroscope": 4.0}
BODY_COLOUR = {"disk": "#4a7fb5", "ring": "#c8a13a", "hurricane": "#7a8a99", "gyroscope": "#7a8a99"}
MARK_COLOUR = "#d62728"
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

    def __init__(self, ax, label: str, model: str, params: dict, arrays: dict, times: np.ndarray, fontsize: float):
        self.ax = ax
        self.kind = kind = geometry.body_kind(model)
        self.mesh = shapes.mesh_for(kind, params)
        self.grid_t = arrays["t"]
        self.times = times
        s = timing.states_at(arrays, times)
        self.pivot_height = geometry.gyroscope_pivot_height(arrays["theta"]) if kind == "gyroscope" else 0.0
        self.rotations = geometry.rotation(s["theta"], s["phi"], s["psi"])
        self.centres = geometry.centre(kind, s["theta"], s["x"], s["y"], params, self.pivot_height)
        self.path = np.stack([arrays["x"], arrays["y"]], -1)  # C on the floor, on the grid
        self.frame_path = np.stack([s["x"], s["y"]], -1)
        if kind == "gyroscope":
            pivot = geometry.pivot_point(arrays["theta"], arrays["phi"], arrays["x"], arrays["y"], self.pivot_height)
            self.trace, self.frame_trace = None, None
            marks = pivot[:, :2]
            self.pivot = pivot[0]
        else:
            self.trace = geometry.contact_point(kind, arrays["theta"], arrays["phi"], arrays["x"], arrays["y"], params)[:, :2]
            self.frame_trace = geometry.contact_point(kind, s["theta"], s["phi"], s["x"], s["y"], params)[:, :2]
            marks = self.trace
        self.base = np.array(to_rgb(BODY_COLOUR[kind]))
        self.mark = np.array(to_rgb(MARK_COLOUR))
        self._frame_camera(np.concatenate([self.path, marks]))
        self._draw_static(label, fontsize)

    def _frame_camera(self, points: np.ndarray) -> None:
        reach = REACH[self.kind]
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
        half = self.span / 2
        m = self.middle
        floor = [[(m[0] - half, m[1] - half, 0), (m[0] + half, m[1] - half, 0),
                  (m[0] + half, m[1] + half, 0), (m[0] - half, m[1] + half, 0)]]
        self.floor = ax.add_collection3d(Poly3DCollection(floor, facecolors="#eef0f2", edgecolors="none", zorder=0))
        self.grid = ax.add_collection3d(Line3DCollection(self._floor_segments(m), colors="#c9ced6", linewidths=0.5, zorder=0.5))
        (self.path_line,) = ax.plot([], [], [], color=PATH_COLOUR, linewidth=1.0, label="C path", zorder=1)
        (self.trace_line,) = ax.plot([], [], [], color=TRACE_COLOUR, linewidth=1.0, label="contact trace", zorder=1)
        if self.kind == "gyroscope":
            p = self.pivot
            ax.plot([p[0], p[0]], [p[1], p[1]], [0, p[2]], color="#555555", linewidth=1.5, zorder=1.5)
        self.body = ax.add_collection3d(Poly3DCollection(self.mesh.quads, linewidths=0.4, zorder=2))
        ax.set_title(label, fontsize=fontsize, pad=0)

    def _inside(self, points: np.ndarray, k: int) -> np.ndarray:
        """``points`` with those off the floor's window set to NaN (mplot3d does not clip lines)."""
        if not self.follow:
            return points
        off = np.any(np.abs(points - self.centres[k, :2]) > self.span / 2, axis=1)
        return np.where(off[:, None], np.nan, points)

    def update(self, k: int) -> list:
        """Move the artists to frame k; returns them (for matplotlib's animation)."""
        t = self.times[k]
        quads, normals = self.mesh.placed(self.rotations[k], self.centres[k])
        light = 0.35 + 0.65 * np.abs(normals @ LIGHT)
        colours = np.where(self.mesh.mark[:, None], self.mark, self.base) * light[:, None]
        self.body.set_verts(quads)
        colours = np.clip(colours, 0, 1)
        self.body.set_facecolor(colours)
        self.body.set_edgecolor(colours)  # edges in the face's colour: no seams between faces
        n = int(np.searchsorted(self.grid_t, t, side="right"))
        path = self._inside(np.concatenate([self.path[:n], self.frame_path[k:k + 1]]), k)
        self.path_line.set_data_3d(path[:, 0], path[:, 1], np.zeros(len(path)))
        if self.trace is not None:
            trace = self._inside(np.concatenate([self.trace[:n], self.frame_trace[k:k + 1]]), k)
            self.trace_line.set_data_3d(trace[:, 0], trace[:, 1], np.zeros(len(trace)))
        if self.follow:
            middle = self.centres[k, :2]
            self._set_limits(middle)
            half = self.span / 2
            self.floor.set_verts([[(middle[0] - half, middle[1] - half, 0), (middle[0] + half, middle[1] - half, 0),
                                   (middle[0] + half, middle[1] + half, 0), (middle[0] - half, middle[1] + half, 0)]])
            self.grid.set_segments(self._floor_segments(middle))
        return [self.body, self.path_line, self.trace_line, self.floor, self.grid]

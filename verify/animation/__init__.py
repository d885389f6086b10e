"""Animations of the rolling bodies in 3D: the disk or hoop, the thick ring, the hurricane balls, the
gyroscope, and any body of revolution from its body file (``body:NAME``), with the slip of a run with friction.

>>> from verify.animation import AnimationRun, animate
>>> run = AnimationRun.from_solution("disk", "disk", sol, {"k": 0.25, "g": 980.0})  # doctest: +SKIP
>>> animate([run], "disk.gif")                                                     # doctest: +SKIP

Modules: :mod:`.run` (the input), :mod:`.geometry` (where the body is, paper Eqs. 7, 47, 63),
:mod:`.shapes` (the drawn meshes), :mod:`.revolution` (a body file's surface and the tippe top's stem),
:mod:`.timing` (speed rule, frames, interpolation), :mod:`.scene` (one panel), :mod:`.animate` (the figure
and the writers).
"""
from __future__ import annotations

from .animate import FORMATS, AnimationRecord, animate, build
from .errors import AnimationError
from .geometry import DRAWN_MODELS
from .run import AnimationRun

__all__ = ["AnimationError", "AnimationRecord", "AnimationRun", "DRAWN_MODELS", "FORMATS", "animate", "build"]

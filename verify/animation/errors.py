"""The one error the animation raises for bad input or a missing tool."""
from __future__ import annotations


class AnimationError(ValueError):
    """A run, an option or an output path the animation cannot use; the message is one line
    naming the value and what is allowed (or how to get what is missing)."""

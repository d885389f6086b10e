"""The progress line on stderr while a single run integrates."""
from __future__ import annotations

import math
import threading
import time

from ..guard import isatty

from .output import _float


PROGRESS_INTERVAL = 1.0  # seconds between progress lines (twice that before the first)


class _Progress:
    """A progress line on stderr while a single run integrates: time reached, steps, rate.

    ``update(t, steps)`` is what solve's ``progress`` hook calls after each step: it only stores
    the pair.  A daemon thread prints at most once a second (on a terminal, one line rewritten in
    place; otherwise a line per report, less often as the run gets long), starting after the
    first two seconds, so that short runs print nothing.
    """

    def __init__(self, stream, label: str, t_end: str, enabled: bool, interval: float | None = None):
        self.stream, self.label, self.t_end, self.enabled = stream, label, t_end, enabled
        self.interval = PROGRESS_INTERVAL if interval is None else interval
        self.t = self.steps = None
        self.t0 = time.monotonic()
        self.tty = isatty(stream)
        self.shown = False
        self._stop = threading.Event()
        self._thread = None

    def update(self, t, steps) -> None:
        self.t, self.steps = t, steps

    def __enter__(self):
        if self.enabled:
            self._thread = threading.Thread(target=self._loop, name="verify-progress", daemon=True)
            self._thread.start()
        return self

    def __exit__(self, *exc):
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
        if self.shown and self.tty:
            self._write("\n")
        return False

    def _loop(self) -> None:
        wait = 2 * self.interval  # runs shorter than that (most, and the JIT) print nothing
        while not self._stop.wait(wait):
            self._write(("\r\x1b[K" if self.tty else "") + self.line() + ("" if self.tty else "\n"))
            self.shown = True
            elapsed = time.monotonic() - self.t0
            wait = self.interval if self.tty or elapsed < 10 * self.interval else 10 * self.interval if elapsed < 600 else 60.0

    def line(self) -> str:
        elapsed = time.monotonic() - self.t0
        t, steps = self.t, self.steps
        if t is None:
            return f"{self.label}: setting up (compiling the equations), t_end = {self.t_end} s, {elapsed:.0f} s elapsed"
        tf, te = _float(t), _float(self.t_end)
        pct = f" ({100 * tf / te:.3g} %)" if te > 0 and math.isfinite(tf) else ""
        rate = steps / elapsed if elapsed > 0 else 0.0
        return (f"{self.label}: t = {tf:.6g} of {self.t_end} s{pct}, {steps:,} steps, {rate:,.0f} steps/s, "
                f"{elapsed:.0f} s elapsed")

    def _write(self, text: str) -> None:
        try:
            self.stream.write(text)
            self.stream.flush()
        except (OSError, ValueError, AttributeError):  # stderr closed (2>&-) or a closed pipe: stop reporting
            self._stop.set()

"""heyoka's log messages, collected instead of printed.

heyoka reports the problems of its event detection (root finding that fails or gives up,
event detection skipped on a non-finite step) only as warnings of its spdlog logger, which
writes them to the process's file descriptor 1 -- the user's stdout, in the middle of JSON --
and carries on.  :func:`collect` redirects descriptor 1 to a temporary file while heyoka
integrates, keeps heyoka's lines as :class:`Message` records for the caller to turn into an
outcome (``failed:event_detection``), and writes every other line back to the real stdout when
the outermost collection ends.  Collections nest and may overlap across threads (a process-wide
lock and count): each sees heyoka's lines written while it was open, so with two runs on two
threads at once each may see the other's warnings (the suite runs in parallel only in
processes).  Output that a progress hook prints to stdout during a run appears when the run
ends; stderr is never touched.
"""
from __future__ import annotations

import ctypes
import os
import re
import sys
import tempfile
import threading
from contextlib import contextmanager
from dataclasses import dataclass

_LINE = re.compile(r"\[heyoka[^\]]*\]\s*\[(?P<level>[a-z]+)\]\s*(?P<text>.*)")
_ANSI = re.compile(r"\x1b\[[0-9;]*m")
_BATCH_INDEX = re.compile(r"batch index (\d+)")


@dataclass(frozen=True)
class Message:
    """One line of heyoka's log: its level (``warning``, ``error``, ...) and text."""

    level: str
    text: str

    @property
    def lane(self):
        """The batch lane the message names ("at the batch index 3"), or None."""
        m = _BATCH_INDEX.search(self.text)
        return int(m.group(1)) if m else None

    @property
    def event_detection(self) -> bool:
        return "event detection" in self.text or "root finding" in self.text or "root isolation" in self.text


class _State:
    lock = threading.Lock()
    depth = 0
    file = None
    saved = None
    spare = None  # the emptied file of the last collection, reused (creating one costs ~50 us a run)
    libc = None


os.register_at_fork(after_in_child=lambda: setattr(_State, "spare", None))  # a child never shares the file


def _fflush() -> None:
    try:
        _State.libc = _State.libc or ctypes.CDLL(None)  # loaded once: each CDLL() builds a class (~20 us)
        _State.libc.fflush(None)
    except (OSError, AttributeError):  # pragma: no cover - no C library to flush
        pass


def _flush_all() -> None:
    for stream in (sys.stdout, sys.__stdout__):
        try:
            if stream is not None:
                stream.flush()
        except (OSError, ValueError):
            pass
    _fflush()


@contextmanager
def collect():
    """Within the block heyoka's log lines go to the list this yields (as :class:`Message`), not to stdout."""
    found: list = []
    with _State.lock:
        active = True
        if _State.depth == 0:
            try:
                _flush_all()
                tmp, _State.spare = _State.spare or tempfile.TemporaryFile(), None
                saved = os.dup(1)
                os.dup2(tmp.fileno(), 1)
                _State.file, _State.saved = tmp, saved
            except OSError:  # no descriptor 1 (a daemon): heyoka cannot print either
                active = False
        if active:
            _State.depth += 1
            start = os.fstat(_State.file.fileno()).st_size
    if not active:
        yield found
        return
    try:
        yield found
    finally:
        with _State.lock:
            _flush_all()
            fd = _State.file.fileno()
            end = os.fstat(fd).st_size
            text = os.pread(fd, end - start, start).decode("utf-8", "replace") if end > start else ""
            for line in text.splitlines():
                m = _LINE.search(_ANSI.sub("", line))
                if m:
                    found.append(Message(m.group("level"), m.group("text").strip()))
            _State.depth -= 1
            if _State.depth == 0:
                whole = os.pread(fd, os.fstat(fd).st_size, 0).decode("utf-8", "replace")
                os.dup2(_State.saved, 1)
                os.close(_State.saved)
                os.ftruncate(fd, 0)
                os.lseek(fd, 0, os.SEEK_SET)  # descriptor 1 shared this offset: the next run writes from 0
                _State.spare, _State.file, _State.saved = _State.file, None, None
                others = [ln for ln in whole.splitlines(keepends=True) if not _LINE.search(_ANSI.sub("", ln))]
                if others:
                    try:
                        os.write(1, "".join(others).encode())
                    except OSError:
                        pass

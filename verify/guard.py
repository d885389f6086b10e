"""The process around one command: stdout kept for the result, and Ctrl-C that always works.

:class:`Session` collects what the command will print (written only after the computation) and
what an interrupt should say; :class:`Guard` points file descriptor 1 at 2 while the command
computes and runs the Ctrl-C watchdog.  :func:`verify.cli.main` holds both.
"""
from __future__ import annotations

import json
import os
import sys
import threading


# --- one invocation: what goes to stdout, what an interrupt should say ----------------------

class Session:
    """Collects the command's stdout (written only after the computation) and its interrupt note."""

    def __init__(self, json_mode: bool):
        self.out: list = []
        self.json_mode = json_mode
        self.interrupt_note = ""

    def emit(self, text: str) -> None:
        self.out.append(text)


def isatty(stream) -> bool:
    try:
        return stream.isatty()
    except (AttributeError, ValueError, OSError):
        return False


# --- stdout while computing -------------------------------------------------------------------

def _flush_c_stdio() -> None:
    """fflush(NULL): C and C++ (std::cout is synced with stdio) output still in the C library's buffers."""
    try:
        import ctypes

        ctypes.CDLL(None).fflush(None)
    except Exception:  # pragma: no cover - no libc to flush
        pass


INTERRUPT_GRACE = 2.0  # seconds the main thread has to act on Ctrl-C before the watchdog does


class Guard:
    """The computation's surroundings: stdout kept clean, and Ctrl-C that always works.

    * While the command computes, file descriptor 1 points at 2 and sys.stdout is sys.stderr:
      what heyoka, LLVM or any library prints cannot corrupt the result, written after.
    * Python acts on Ctrl-C only between bytecodes, so inside one long C++ call (heyoka compiling
      a Taylor integrator at mp:100000, or at --tol 1e-300 in double, takes minutes) it would wait
      for the call to return.  A watchdog thread, woken by the signal itself (signal.set_wakeup_fd),
      gives the main thread INTERRUPT_GRACE seconds to raise KeyboardInterrupt; if it does not, the
      watchdog writes the same one line (and, under --format json, the error document) and ends the
      process with status 130, as a kill would: a sweep's store loses at most the chunk in flight.
    """

    def __init__(self, session: Session, err):
        self.session, self.err = session, err
        self.saved = None  # the real stdout, while fd 1 points at stderr
        self.back = threading.Event()  # the main thread is back in Python
        self.closing = False
        self.pipe = self.old_wakeup = self.thread = None

    def __enter__(self):
        self._redirect()
        self._watch()
        return self

    def __exit__(self, *exc):
        self.back.set()
        self._unwatch()
        self._restore()
        return False

    # stdout
    def _redirect(self) -> None:
        try:
            sys.stdout.flush()
        except (AttributeError, OSError, ValueError):
            pass
        _flush_c_stdio()
        try:
            self.saved = os.dup(1)
        except OSError:  # fd 1 closed (>&-): nothing to protect; keep it occupied while we compute
            self.saved = None
        try:
            os.dup2(2, 1)
        except OSError:  # fd 2 closed (2>&-): send it nowhere
            try:
                devnull = os.open(os.devnull, os.O_WRONLY)
                if devnull != 1:
                    os.dup2(devnull, 1)
                    os.close(devnull)
            except OSError:
                pass
        self.old_stdout = sys.stdout
        sys.stdout = sys.stderr

    def _restore(self) -> None:
        sys.stdout = self.old_stdout
        try:
            sys.stderr.flush()
        except (AttributeError, OSError, ValueError):
            pass
        _flush_c_stdio()
        if self.saved is not None:
            os.dup2(self.saved, 1)
            os.close(self.saved)
            self.saved = None
        else:  # fd 1 was closed: close it again
            try:
                os.close(1)
            except OSError:
                pass

    # Ctrl-C
    def _watch(self) -> None:
        import signal

        if threading.current_thread() is not threading.main_thread():
            return  # set_wakeup_fd is the main thread's; Python's own handling remains
        r, w = os.pipe()
        os.set_blocking(w, False)
        try:
            self.old_wakeup = signal.set_wakeup_fd(w, warn_on_full_buffer=False)
        except (ValueError, OSError):
            os.close(r)
            os.close(w)
            return
        self.pipe = (r, w)
        self.thread = threading.Thread(target=self._watchdog, name="verify-interrupt", daemon=True)
        self.thread.start()

    def _unwatch(self) -> None:
        import signal

        if self.pipe is None:
            return
        try:
            signal.set_wakeup_fd(self.old_wakeup if self.old_wakeup is not None else -1)
        except (ValueError, OSError):
            pass
        self.closing = True
        try:
            os.write(self.pipe[1], b"\0")
        except OSError:
            pass
        self.thread.join()
        for fd in self.pipe:
            os.close(fd)
        self.pipe = None

    def _watchdog(self) -> None:
        import signal

        while True:
            try:
                data = os.read(self.pipe[0], 64)
            except OSError:
                return
            if self.closing or not data:
                return
            if signal.SIGINT in data and not self.back.wait(INTERRUPT_GRACE):
                self._hard_interrupt()

    def _hard_interrupt(self) -> None:
        line = interrupted_line(self.session)
        if self.session.json_mode and not self.session.out and self.saved is not None:
            try:
                os.write(self.saved, (json.dumps({"error": line, "exit_status": 130}) + "\n").encode())
            except OSError:
                pass
        try:
            self.err.write(("\r\x1b[K" if isatty(self.err) else "") + f"error: {line}\n")
            self.err.flush()
        except (OSError, ValueError, AttributeError):
            pass
        os._exit(130)


def interrupted_line(session: Session) -> str:
    return f"interrupted (Ctrl-C){': ' + session.interrupt_note if session.interrupt_note else ''}"

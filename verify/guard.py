"""The process around one command: stdout kept for the result, and Ctrl-C that always works.

:class:`Session` collects what the command will print (written only after the computation) and
what an interrupt should say; :class:`Guard` points file descriptor 1 at 2 while the command
computes.  :func:`verify.cli.main` holds both.

:func:`supervise` (``python -m verify`` calls it first, before anything heavy is imported) makes
Ctrl-C work even inside one long C++ call: the command runs in a child process and the process the
shell started only waits for it, so nothing in that process ever waits for the child's GIL.
"""
from __future__ import annotations

import json
import os
import select
import signal
import sys
import time


# --- one invocation: what goes to stdout, what an interrupt should say ----------------------

class Session:
    """Collects the command's stdout (written only after the computation) and its interrupt note.

    The note (a sweep's "rerun the same command to resume") is also told to the supervisor, which
    says it if it has to end the command itself.
    """

    def __init__(self, json_mode: bool):
        self.out: list = []
        self.json_mode = json_mode
        self._note = ""

    def emit(self, text: str) -> None:
        self.out.append(text)

    @property
    def interrupt_note(self) -> str:
        return self._note

    @interrupt_note.setter
    def interrupt_note(self, note: str) -> None:
        self._note = note
        _report("note", note)


def wants_json(argv: list) -> bool:
    """``--format json`` on the line: read before parsing (the supervisor does not parse)."""
    for i, tok in enumerate(argv):
        if tok == "--format=json" or (tok == "--format" and i + 1 < len(argv) and argv[i + 1] == "json"):
            return True
    return False


def interrupted_line(session: Session) -> str:
    return _interrupted(session.interrupt_note)


def _interrupted(note: str) -> str:
    return f"interrupted (Ctrl-C){': ' + note if note else ''}"


def isatty(stream) -> bool:
    try:
        return stream.isatty()
    except (AttributeError, ValueError, OSError):
        return False


# --- stdout while computing -------------------------------------------------------------------

def _flush_c_stdio() -> None:
    """fflush(NULL): C and C++ (std::cout is synced with stdio) output still in the C library's buffers."""
    try:
        import ctypes  # lazy: ctypes (3 ms) only in the command's process, not the supervisor or 'import verify.cli'

        ctypes.CDLL(None).fflush(None)
    except Exception:  # pragma: no cover - no libc to flush
        pass


class Guard:
    """The computation's surroundings: stdout kept clean while the command computes.

    While the command computes, file descriptor 1 points at 2 and sys.stdout is sys.stderr: what
    heyoka, LLVM or any library prints cannot corrupt the result, written after.  It tells the
    supervisor (if any) when the computation starts and ends: only in between may the supervisor
    end the command on Ctrl-C (before and after, the command is in Python, and says it itself).
    """

    def __init__(self, session: Session, err):
        self.session, self.err = session, err
        self.saved = None  # the real stdout, while fd 1 points at stderr
        self.redirected = False

    def __enter__(self):
        try:
            _report("computing")
            self._redirect()
        except BaseException:  # Ctrl-C on the way in: the way out all the same (no __exit__ follows)
            self.__exit__()
            raise
        return self

    def __exit__(self, *exc):
        _report("back")  # before anything is written: the result, or the error line
        self._restore()
        return False

    def _redirect(self) -> None:
        self.old_stdout = sys.stdout
        try:
            sys.stdout.flush()
        except (AttributeError, OSError, ValueError):
            pass
        _flush_c_stdio()
        try:
            self.saved = os.dup(1)
        except OSError:  # fd 1 closed (>&-): nothing to protect; keep it occupied while we compute
            self.saved = None
        self.redirected = True  # from here, _restore puts fd 1 back
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
        sys.stdout = sys.stderr

    def _restore(self) -> None:
        if not self.redirected:
            return
        self.redirected = False
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


# --- Ctrl-C: a supervisor process that needs no GIL but its own ------------------------------

INTERRUPT_GRACE = 2.0  # seconds the command has to act on Ctrl-C before the supervisor does

_report_fd = None  # in the supervised child: its end of the pipe to the supervisor


def _report(kind: str, text: str = "") -> None:
    """Tell the supervisor (if any) what it needs should it have to end the command itself."""
    if _report_fd is None:
        return
    try:  # one short line: a single write, atomic on a pipe; never blocks (non-blocking fd)
        os.write(_report_fd, (json.dumps([kind, text]) + "\n").encode())
    except OSError:
        pass


def supervise(argv: list) -> None:
    """Run the command in a child process; return only in that child.  The parent never returns.

    Python acts on Ctrl-C only between bytecodes, and heyoka's JIT can hold the GIL for minutes
    inside one C++ call (a Taylor integrator at mp:100000, or at --tol 1e-300 in double), so no
    thread of the computing process can be relied on to act: a watchdog thread waits for the same
    GIL.  So the process the shell started (the parent) forks before anything heavy is imported,
    while it has a single thread, and from then on only waits for the child: on SIGINT it gives
    the child :data:`INTERRUPT_GRACE` seconds to act on it (the child says the one line, and a
    sweep's note, itself); if the child does not, the parent kills it and writes that line (and,
    under ``--format json``, the error document) itself, and exits 130: the same status the shell
    and ``Popen.returncode`` see as when the child acts.  Otherwise the parent exits as the child
    did: with its status, or killed by the same signal.

    * The terminal sends Ctrl-C to the whole process group, a ``kill -INT`` to the parent alone,
      so the child ignores SIGINT and acts on the SIGUSR1 the parent sends it instead: exactly
      one KeyboardInterrupt either way.
    * The child reports, over a pipe, a sweep's interrupt note and when it enters and leaves the
      computation (:class:`Guard`); it writes its result or its error line only after.  After the
      grace the parent stops the child (SIGSTOP, waited for) and reads the pipe: a child that is
      not computing is in Python and about to say it, so it is let go on (SIGCONT).  Never two
      error lines, never two documents.
    * On Linux the child asks the kernel to kill it when the parent dies (PR_SET_PDEATHSIG), so
      a SIGTERM or SIGKILL of the command leaves no computation running.

    Without fork (Windows), or with threads already running (a fork would copy none of them),
    the command runs in this process with Python's own Ctrl-C.
    """
    global _report_fd
    if not hasattr(os, "fork") or not _single_threaded():
        return
    held = {signal.SIGINT, signal.SIGUSR1, signal.SIGCHLD}  # until each side has its handlers
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, held)
    parent = os.getpid()
    try:
        report_r, report_w = _pipe()
        wake_r, wake_w = _pipe()
        pid = os.fork()
    except OSError:  # no fork today: run the command here
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        return
    if pid == 0:
        for fd in (report_r, wake_r, wake_w):
            os.close(fd)
        _die_with(parent)
        signal.signal(signal.SIGINT, _ignore)  # a handler, not SIG_IGN: programs it runs get the default
        signal.signal(signal.SIGUSR1, signal.default_int_handler)
        os.set_blocking(report_w, False)
        _report_fd = report_w
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        return
    os.close(report_w)
    _Supervisor(pid, report_r, wants_json(argv)).wait(wake_r, wake_w, mask)


def _ignore(signum, frame) -> None:
    pass


def _single_threaded() -> bool:
    try:
        return len(os.listdir("/proc/self/task")) == 1
    except OSError:
        import threading  # lazy: threading (3 ms) only where /proc/self/task is missing (not Linux)

        return threading.active_count() == 1


def _pipe() -> tuple:
    """A pipe whose two ends are neither 0, 1 nor 2: with stdout closed (``>&-``) os.pipe would
    hand out fd 1, and the child would take the pipe for its stdout."""
    import fcntl  # lazy: POSIX only; supervise calls this only where os.fork exists

    ends = []
    for fd in os.pipe():
        if fd < 3:
            fd, low = fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 3), fd
            os.close(low)
        ends.append(fd)
    return tuple(ends)


def _die_with(parent: int) -> None:
    """Linux: have the kernel SIGKILL this child when its parent, the supervisor, dies."""
    try:
        import ctypes  # lazy: as in _flush_c_stdio

        ctypes.CDLL(None).prctl(1, int(signal.SIGKILL))  # PR_SET_PDEATHSIG
    except (OSError, AttributeError):  # not Linux
        return
    if os.getppid() != parent:  # it died before we asked
        os._exit(1)


class _Supervisor:
    """The parent's side: wait for the child, forward Ctrl-C, end the child after the grace."""

    def __init__(self, pid: int, reports: int, json_mode: bool):
        self.pid, self.reports, self.json_mode = pid, reports, json_mode
        self.note, self.computing, self.buffer, self.reports_open = "", False, b"", True
        os.set_blocking(reports, False)

    def wait(self, wake_r: int, wake_w: int, mask) -> None:
        os.set_blocking(wake_w, False)
        signal.set_wakeup_fd(wake_w, warn_on_full_buffer=False)  # every signal wakes select
        signal.signal(signal.SIGINT, _ignore)
        signal.signal(signal.SIGCHLD, _ignore)
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)
        deadline, interrupted = None, False
        while True:
            self._exit_if_done(os.WNOHANG)
            timeout = None if deadline is None else deadline - time.monotonic()
            if timeout is not None and timeout <= 0:
                if self._stopped_computing():
                    self._end_child()
                deadline = None  # in Python, not computing: the interrupt is the child's to report
                continue
            ready = select.select([wake_r] + ([self.reports] if self.reports_open else []), [], [], timeout)[0]
            if self.reports in ready:
                self._read()
            if wake_r in ready and signal.SIGINT in os.read(wake_r, 64) and not interrupted:
                interrupted = True  # once: a second Ctrl-C would interrupt the child's report of the first
                os.kill(self.pid, signal.SIGUSR1)  # the child's KeyboardInterrupt
                deadline = time.monotonic() + INTERRUPT_GRACE

    def _exit_if_done(self, flags: int) -> None:
        """Exit as the child did, if it has ended: with its status, or by the same signal."""
        pid, status = os.waitpid(self.pid, flags)
        if pid == 0 or os.WIFSTOPPED(status):
            return
        if os.WIFSIGNALED(status):
            sig = os.WTERMSIG(status)
            try:
                signal.signal(sig, signal.SIG_DFL)
                signal.pthread_sigmask(signal.SIG_UNBLOCK, {sig})
            except (OSError, ValueError):  # SIGKILL and SIGSTOP need neither
                pass
            os.kill(os.getpid(), sig)
            os._exit(128 + sig)  # a signal whose default is not to end the process
        os._exit(os.WEXITSTATUS(status))

    def _stopped_computing(self) -> bool:
        """Stop the child and read all it has reported: is it still computing?  If so it stays
        stopped, to be killed; if not it goes on (SIGCONT) to say its own end."""
        os.kill(self.pid, signal.SIGSTOP)
        self._exit_if_done(os.WUNTRACED)  # returns once it has stopped: it reports nothing more
        self._read()
        if not self.computing:
            os.kill(self.pid, signal.SIGCONT)
        return self.computing

    def _read(self) -> None:
        while True:
            try:
                data = os.read(self.reports, 4096)
            except BlockingIOError:
                return
            if not data:  # closed: the child has ended (reaped on SIGCHLD)
                self.reports_open = False
                return
            self.buffer += data
            *lines, self.buffer = self.buffer.split(b"\n")
            for line in lines:
                kind, text = json.loads(line)
                if kind == "note":
                    self.note = text
                else:
                    self.computing = kind == "computing"

    def _end_child(self) -> None:
        """The child did not act on Ctrl-C within the grace: end it, say what it would have, exit 130."""
        os.kill(self.pid, signal.SIGKILL)
        os.waitpid(self.pid, 0)
        line = _interrupted(self.note)
        if self.json_mode:  # still computing: it has written nothing to stdout
            _write(1, json.dumps({"error": line, "exit_status": 130}) + "\n")
        _write(2, ("\r\x1b[K" if os.isatty(2) else "") + f"error: {line}\n")
        os._exit(130)


def _write(fd: int, text: str) -> None:
    try:
        os.write(fd, text.encode())
    except OSError:  # closed (>&-, 2>&-) or the reader gone: nothing more to do
        pass

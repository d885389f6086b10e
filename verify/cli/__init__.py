"""Command line: ``python -m verify {trajectory,models,threshold,spindown,reference,score,sweep,report,bench} ...``.

Exit statuses: 0 done; 1 a failed integration (or a run the integrator does not mark ``ok`` or
``event:...``), a study that found no root, or an unexpected error; 2 bad input; 130 interrupted
(Ctrl-C); 141 stdout closed under us (``| head``).  Every failure is one line on stderr naming
the bad value and what is allowed; ``--debug`` (anywhere on the line) adds the Python traceback of
an unexpected error.  Under ``--format json`` stdout holds exactly one JSON document (on failure
``{"error": ..., "exit_status": ...}``): whatever heyoka or C++ prints during a computation goes to
stderr (file descriptor 1 is pointed at 2 while the command runs), and the result is written after.

This package is the entry point (:func:`main`: exit statuses, the result written last);
:mod:`.parser` (the options), :mod:`.arguments` (reading their values), :mod:`.commands` (one function
a command), :mod:`.output` (records, text, JSON), :mod:`.progress` (the progress line).
"""
from __future__ import annotations

import json
import os
import sys

from ..engine.errors import IntegrationError
from ..guard import Guard, Session, interrupted_line, wants_json
from .arguments import RunFailed, UsageError
from .parser import _prepare, parser


# --- main -------------------------------------------------------------------------------------

def _say(stream, line: str) -> None:
    if stream is None:  # stderr closed (2>&-): print(file=None) would write to stdout
        return
    try:
        print(line, file=stream, flush=True)
    except (OSError, ValueError, AttributeError):  # stderr closed: nothing more we can do
        pass


def main(argv=None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    out, err = sys.stdout, sys.stderr
    session = Session(wants_json(argv))
    debug = "--debug" in argv

    def fail(code: int, line: str) -> int:
        line = " ".join(line.split())  # one line, whatever the message (mpmath's have two)
        if session.json_mode and not session.out:
            session.emit(json.dumps({"error": line, "exit_status": code}))
        _say(err, f"error: {line}")
        return code

    code = 0
    try:
        try:
            ap = parser()
            argv, debug = _prepare(argv, ap)
            try:
                args = ap.parse_args(argv)
            except SystemExit as exc:  # --help
                code = exc.code if isinstance(exc.code, int) else 0
                return code
            with Guard(session, err):
                code = args.run(args, session)
        except UsageError as exc:
            code = fail(2, str(exc))
        except RunFailed as exc:
            code = fail(1, str(exc))
        except (IntegrationError, RuntimeError) as exc:  # a failed run or a study that found no root
            if debug:
                import traceback  # lazy: traceback (3 ms) only with --debug; not loaded by '--help'

                traceback.print_exc(file=err)
            code = fail(1, str(exc) or type(exc).__name__)
        except KeyboardInterrupt:
            if debug:
                import traceback  # lazy: traceback (3 ms) only with --debug; not loaded by '--help'

                traceback.print_exc(file=err)
            code = fail(130, interrupted_line(session))
        except BrokenPipeError:
            raise
        except Exception as exc:  # noqa: BLE001 - the CLI shows no traceback unless asked
            if debug:
                import traceback  # lazy: traceback (3 ms) only with --debug; not loaded by '--help'

                traceback.print_exc(file=err)
                code = fail(1, f"unexpected {type(exc).__name__}: {_one_line(exc)}")
            else:
                code = fail(1, f"unexpected {type(exc).__name__}: {_one_line(exc)} "
                               "(a bug; rerun with --debug for the traceback)")
        if session.out and out is None:  # stdout closed (>&-)
            _say(err, "error: stdout is closed; the result was not written")
            return code or 1
        for text in session.out:
            out.write(text + "\n")
        if out is not None:
            out.flush()
        return code
    except BrokenPipeError:
        # The reader went away (| head): stop quietly.  Point stdout at devnull so that the
        # interpreter's final flush does not fail again, and exit as a process killed by SIGPIPE.
        try:
            devnull = os.open(os.devnull, os.O_WRONLY)
            os.dup2(devnull, out.fileno())
            os.close(devnull)
        except (OSError, ValueError, AttributeError):
            pass
        return 141
    except KeyboardInterrupt:  # while writing the result
        _say(err, f"error: {interrupted_line(session)}")
        return 130


def _one_line(exc: BaseException) -> str:
    text = " ".join(str(exc).split())
    return text[:300] + ("..." if len(text) > 300 else "") if text else "(no message)"

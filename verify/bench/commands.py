"""The command line's own speed: the listings, one paper figure after compilation, an animation of a 2 s run.

Each command runs in a fresh process (``python -m verify ...``) as a person would type it; its CPU
time (user + system, from ``os.wait4``) and wall time are recorded, and the listings are also given
as a ratio to the bare interpreter's start (``python -c pass``) measured in the same run, so the
number says what the command adds.  ``figure 5`` and ``animate`` are run once first (heyoka's
compiled code is then in its disk cache, as on every run after a user's first) and timed the
second time.  Nothing here asserts; the tests check what is imported, not how long it takes.
"""
from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

#: (label, arguments after ``python -m verify``, warm-up first)
COMMANDS = (
    ("--help", ["--help"], False),
    ("models", ["models"], False),
    ("starts", ["starts"], False),
    ("figure --list", ["figure", "--list"], False),
    ("figure 5 (after compilation)", ["figure", "5", "--out", "{dir}"], True),
    ("animate disk, 2 s run, GIF", ["animate", "disk", "--t-end", "2", "--out", "{dir}/disk.gif"], True),
)


def _timed(argv: list, cwd: str) -> tuple:
    """(cpu seconds, wall seconds, exit status) of one process."""
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[2]))
    t0 = time.monotonic()
    p = subprocess.Popen(argv, cwd=cwd, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    return usage.ru_utime + usage.ru_stime, time.monotonic() - t0, p.returncode


def command_speed(quick: bool, progress=None) -> dict:
    """CPU and wall time of each command of :data:`COMMANDS`, and the interpreter's start for scale."""
    rounds = 1 if quick else 3
    with tempfile.TemporaryDirectory() as folder:
        base = min(_timed([sys.executable, "-c", "pass"], folder)[0] for _ in range(rounds))
        rows = []
        for label, args, warm in COMMANDS:
            if quick and warm and "animate" in label:
                continue
            argv = [sys.executable, "-m", "verify", *(a.replace("{dir}", folder) for a in args)]
            if warm:
                _timed(argv, folder)
            runs = [_timed(argv, folder) for _ in range(1 if warm else rounds)]
            cpu, wall, status = min(runs)
            rows.append({"command": label, "cpu_s": round(cpu, 3), "wall_s": round(wall, 3), "exit_status": status,
                         "cpu_over_interpreter_start": round(cpu / base, 1) if base > 0 else None})
            if progress:
                progress(f"command line: {label}: {cpu:.2f} s CPU")
    return {"interpreter_start_cpu_s": round(base, 3), "rounds": rounds, "commands": rows}

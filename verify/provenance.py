"""What produced a report: versions, the commit and a hash of the sources, the precisions used."""
from __future__ import annotations

import hashlib
import os
import platform
import subprocess
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
SOURCE_DIRS = ("models", "verify")
SOURCE_PATHS = SOURCE_DIRS + ("pyproject.toml",)


def source_hash() -> str:
    """sha256 over the Python sources of models/ and verify/ (paths and contents)."""
    h = hashlib.sha256()
    for d in SOURCE_DIRS:
        for path in sorted((ROOT / d).rglob("*.py")):
            h.update(str(path.relative_to(ROOT)).encode())
            h.update(b"\0")
            h.update(path.read_bytes())
    return h.hexdigest()


def source_commit() -> dict:
    """The last git commit that changed the sources, and whether the working tree differs from it.

    The commit of the *sources* (models/, verify/, pyproject.toml), not HEAD: a commit that
    only adds regenerated reports does not change it, so regenerating a committed report
    gives the same bytes.  ``None`` outside a git checkout.
    """
    def git(*args):
        return subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True, check=True).stdout.strip()

    try:
        commit = git("log", "-1", "--format=%H", "--", *SOURCE_PATHS)
        modified = bool(git("status", "--porcelain", "--", *SOURCE_PATHS))
    except (OSError, subprocess.CalledProcessError):
        return {"commit": None, "modified": None}
    return {"commit": commit or None, "modified": modified}


def versions() -> dict:
    import heyoka  # lazy: 1.5 s for the six; 'report' input checks import this module
    import matplotlib  # lazy: as heyoka
    import mpmath  # lazy: as heyoka
    import numpy  # lazy: as heyoka
    import PIL  # lazy: as heyoka
    import sympy  # lazy: as heyoka

    return {
        "python": platform.python_version(),
        "heyoka": heyoka.__version__,
        "numpy": numpy.__version__,
        "mpmath": mpmath.__version__,
        "sympy": sympy.__version__,
        "matplotlib": matplotlib.__version__,
        "pillow": PIL.__version__,  # encodes the figures (PNG) and the page's embedded copies (WebP)
    }


def cpu_model() -> str:
    """The CPU's model name (``/proc/cpuinfo``), or "unknown"."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return "unknown"


def provenance(precisions) -> dict:
    """Versions, the sources' commit and hash, and the precisions used (ladder order, no repeats)."""
    from .precision import parse_precision  # lazy: heyoka (1 s); 'report' input checks import this module

    used = sorted({parse_precision(p) for p in precisions}, key=lambda p: (p.bits, p.name))
    return {"versions": versions(), "source_commit": source_commit(), "source_sha256": source_hash(),
            "precisions": [p.name for p in used]}


def writable_folder(folder) -> Path:
    """Create ``folder`` if needed and prove a file can be written there, before any long run.

    Raises ``ValueError`` naming the folder when it cannot be made or written (so a command
    fails in a second, not after the run it would have saved).
    """
    folder = Path(folder)
    try:
        folder.mkdir(parents=True, exist_ok=True)
        fd, probe = tempfile.mkstemp(dir=folder, prefix=".write-probe.", suffix=".tmp")
        os.close(fd)
        os.unlink(probe)
    except OSError as err:
        raise ValueError(f"cannot write to the folder {str(folder)!r}: {err.strerror or err}") from None
    return folder


def write_atomic(path: Path, data: bytes | str) -> None:
    """Write a file so that readers see either the old or the whole new content."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
